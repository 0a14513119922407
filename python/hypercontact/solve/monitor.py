"""What each Newton iterate of a solve did: the norm of the Newton update,
the contacts' active-set and stick/slip signatures and each slave point's
status and master facet. The step's chattering counts and a failed attempt's story are read
from it."""
import numpy as np
from mpi4py import MPI

from .. import _dolfinx as dfx

#: slave points listed per kind of flip in a failed attempt's story
TOP_FLIPPERS = 5
#: nodes listed by the size of their residual force in a failed attempt's story
TOP_RESIDUALS = 5
STATUS_NAMES = {0: "open", 1: "stick", 2: "slip"}


def largest_residuals(model, F, top=TOP_RESIDUALS):
    """Where the residual F (the unknown's layout, at the model's current u) is
    left: the ``top`` displacement nodes of all ranks with the largest residual
    force |r| (the norm of a node's three rows), each with its reference and
    current coordinates, r itself, and the contacts whose slave point sits on
    the node with that point's status (open / stick / slip). Collective."""
    V, u = model.V, model.u
    rows = model.displacement_rows()
    owned = len(rows)
    r = F.array_r[rows] if owned else np.zeros((0, 3))
    X = dfx.node_coordinates(V)[:owned]
    x = X + u.x.array[: 3 * owned].reshape(-1, 3)
    size = model.comm.allreduce(float(np.ptp(X, axis=0).max()) if owned else 0.0, op=MPI.MAX)
    magnitude = np.linalg.norm(r, axis=1)
    mine = np.argsort(-magnitude, kind="stable")[:top]
    slaves = {i: [] for i in mine}
    for c in model.contacts:
        reference, _ = c.point_coordinates(u)  # collective for deformable masters
        status = c.point_status()
        for i in mine:
            near = np.flatnonzero(np.abs(reference - X[i]).max(axis=1) <= 1e-9 * size) if len(reference) else []
            slaves[i] += [{"contact": c.name, "status": status_name(c, status[p])} for p in near]
    local = [{"force": float(magnitude[i]), "point": X[i].tolist(), "current": x[i].tolist(),
              "residual": r[i].tolist(), "slave_of": slaves[i]} for i in mine]
    every = [e for part in model.comm.allgather(local) for e in part]
    return sorted(every, key=lambda e: (-e["force"], e["point"]))[:top]


def status_name(contact, status):
    """open / stick / slip; a frictionless contact's closed point (status 2, it slides) is "closed"."""
    if int(status) == 2 and not contact.frictional:
        return "closed"
    return STATUS_NAMES.get(int(status), str(int(status)))


def describe_residual(entry):
    """One line for the log: where the largest residual force of a failed attempt is."""
    point = ", ".join(f"{v:.4g}" for v in entry["point"])
    now = ", ".join(f"{v:.4g}" for v in entry["current"])
    slaves = "".join(f", slave point of {s['contact']!r} ({s['status']})" for s in entry["slave_of"])
    return f"largest residual force {entry['force']:.3g} at the node ({point}), now at ({now}){slaves}"


class IterationHistory:
    """Filled by :meth:`monitor` (a SNES monitor) from the contacts'
    evaluation at each iterate."""

    def __init__(self, contacts):
        self.contacts = contacts
        self.reset()

    def reset(self):
        self.active_sets, self.stick_slip_sets, self.update_norms = [], [], []
        self.point_states, self.point_facets = [], []

    def monitor(self, snes, its, norm):
        if its == 0:
            self.reset()
        else:
            self.update_norms.append(snes.getSolutionUpdate().norm())
        self.active_sets.append([c.active_set_signature() for c in self.contacts])
        self.stick_slip_sets.append([c.stick_slip_signature() for c in self.contacts if c.frictional])
        self.point_states.append([c.point_status() for c in self.contacts])
        self.point_facets.append([c.point_facets() for c in self.contacts])

    def active_set_changes(self):
        """Newton iterations of the last solve in which some contact's active
        set changed: the chattering count of the step."""
        sets = self.active_sets
        return sum(1 for a, b in zip(sets, sets[1:]) if a != b)

    def stick_slip_changes(self):
        """Newton iterations of the last solve in which some frictional
        contact's stick/slip set changed."""
        sets = self.stick_slip_sets
        return sum(1 for a, b in zip(sets, sets[1:]) if a != b)

    def last_active_set_change(self):
        """Index of the first Newton iterate from which the active set stayed fixed."""
        k = len(self.active_sets) - 1
        while k > 0 and self.active_sets[k - 1] == self.active_sets[-1]:
            k -= 1
        return k

    def flip_story(self, u, comm, top=TOP_FLIPPERS):
        """Per iteration the number of slave points (all ranks) that changed
        open ↔ closed, stick ↔ slip and (closed before and after, against a
        deformable master) their master facet, and the ``top`` points that did
        so most often, with their reference and current coordinates. A point
        that switches facets every iteration sits on a kink of the master
        (e.g. exactly over an edge between two facets). Collective."""
        histories = self.point_states
        per_iteration = np.zeros((3, max(len(histories) - 1, 0)), dtype=np.int64)
        found = {"open_closed": [], "stick_slip": [], "master_facet": []}
        for i, c in enumerate(self.contacts):
            s = np.array([h[i] for h in histories]) if len(histories) > 1 else np.zeros((1, 0), np.int8)
            fa = np.array([h[i] for h in self.point_facets]) if len(histories) > 1 else s.astype(np.int32)
            before, after = s[:-1], s[1:]
            flips = {"open_closed": (before > 0) != (after > 0),
                     "stick_slip": (before > 0) & (after > 0) & (before != after),
                     "master_facet": (before > 0) & (after > 0) & (fa[:-1] != fa[1:])}
            per_iteration += np.array([f.sum(axis=1) for f in flips.values()], dtype=np.int64)
            reference, current = c.point_coordinates(u)  # collective for deformable masters
            for kind, f in flips.items():
                counts = f.sum(axis=0)
                found[kind] += [(int(counts[p]), c.name, reference[p].tolist(), current[p].tolist())
                                for p in np.argsort(-counts, kind="stable")[:top] if counts[p] > 0]
        comm.Allreduce(MPI.IN_PLACE, per_iteration, op=MPI.SUM)
        story = {"open_closed_flips_per_iteration": per_iteration[0].tolist(),
                 "stick_slip_flips_per_iteration": per_iteration[1].tolist(),
                 "master_facet_flips_per_iteration": per_iteration[2].tolist()}
        for kind, local in found.items():
            every = sorted((e for part in comm.allgather(local) for e in part), key=lambda e: (-e[0], e[1], e[2]))
            story[f"most_{kind}_flips"] = [{"contact": name, "flips": n, "point": point, "current": now}
                                           for n, name, point, now in every[:top]]
        return story
