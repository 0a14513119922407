"""What each Newton iterate of a solve did: the norm of the Newton update,
the contacts' active-set and stick/slip signatures and each slave point's
status and master facet. The step's chattering counts and a failed attempt's story are read
from it."""
import numpy as np
from mpi4py import MPI

#: slave points listed per kind of flip in a failed attempt's story
TOP_FLIPPERS = 5


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
