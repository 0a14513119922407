"""A contact pair: geometry × law × enforcement behind one protocol.

Per Newton iterate the solver calls :meth:`Contact.prepare` once; the
residual, the tangent, the monitor (active set, stick/slip, per-point status)
and, after a converged solve, the augmented-Lagrangian test, the commit and
the results all read that one evaluation. Between steps: :meth:`commit` after
a converged step, :meth:`restore` after a failed one; :meth:`state_dict` /
:meth:`load_state_dict` for checkpoints; :meth:`observables` and
:meth:`point_fields` for the results.
"""
import numpy as np
from mpi4py import MPI

from . import kernels
from .kernels import SLIP, STICK
from .law import Frictionless

OFF = Frictionless()  # the law a switched-off pair is evaluated with (gaps only)


class Contact:
    """One slave surface against one master (rigid obstacle or surface)."""

    def __init__(self, name, geometry, law, enforcement, eps_n, smoothing, entry):
        """``entry``: the scene's contact entry it was built from (read, never changed)."""
        self.name, self.geometry, self.law, self.enforcement = name, geometry, law, enforcement
        self.eps_n, self.smoothing, self.entry = float(eps_n), float(smoothing), entry
        self.comm = geometry.comm
        self.evaluation = None
        self.index = 0  # of its [[contact]] entry (the load path's channels)
        #: the share of ε_N the pair acts with (the load path's ("active", j)): 1; ramped 0 → 1 over a
        #: phase that switches it on; 0: switched off — no force, no tangent, and each commit
        #: forgets the friction history (switched on again, every point starts open)
        self.scale = 1.0

    @property
    def frictional(self):
        return self.law.frictional

    @property
    def augmented(self):
        return self.enforcement.augmented

    @property
    def deformable(self):
        """Whether the master is a surface of the mesh (global assembly, a pattern that follows the pairing)."""
        return self.geometry.assembly == "global"

    def set_load_factor(self, load_factor):
        self.geometry.set_load_factor(load_factor)

    @property
    def on(self):
        return self.scale > 0.0

    def set_path_values(self, translation, angle, mu, scale=1.0):
        """Where the load path has the obstacle (rigid: translation from its
        place in the scene, rotation angle), μ now (a frictional law) and
        the share of its penalty the pair acts with (0: switched off)."""
        if translation is not None:
            self.geometry.set_pose(translation, angle)
        if self.law.frictional and self.law.mu != mu:
            self.law.mu = float(mu)
        self.scale = float(scale)

    # --- one evaluation per iterate ------------------------------------------------
    def prepare(self, u):
        """Evaluate the contact at displacement u (collective for surfaces).
        Switched off: the gaps only (a frictionless evaluation whose
        pressure, force and elements nothing reads)."""
        if self.on:
            self.evaluation = kernels.evaluate(self.geometry, self.law, self.enforcement.multipliers,
                                               self.scale * self.eps_n, self.smoothing, self.geometry.coordinates(u))
        else:
            self.evaluation = kernels.evaluate(self.geometry, OFF, np.zeros_like(self.enforcement.multipliers),
                                               self.eps_n, self.smoothing, self.geometry.coordinates(u))

    @property
    def state(self):
        """The prepared evaluation's per-point and total state."""
        return self.evaluation.state

    def evaluate(self, u):
        """Prepare at u and return the state (a driver script's or a test's look at a state)."""
        self.prepare(u)
        return self.state

    def force(self, u=None):
        """Total force of the master on the slave body (all ranks), at u or at the prepared state."""
        if u is not None:
            self.prepare(u)
        force = self.state.force if self.on else np.zeros(3)
        return self.comm.allreduce(force, op=MPI.SUM)

    def num_closed(self, u=None):
        """Closed slave points (all ranks), at u or at the prepared state (0 switched off)."""
        if u is not None:
            self.prepare(u)
        return self.comm.allreduce(self.state.num_closed if self.on else 0, op=MPI.SUM)

    def contact_area(self):
        """Reference area of the slave points that carry pressure at the prepared state (all ranks):
        each point's weight (nodal area or Gauss weight), so it resolves the contact zone's edge to
        about one point spacing."""
        local = float(self.geometry.point_area[self.state.pressure > 0.0].sum()) if self.on else 0.0
        return self.comm.allreduce(local, op=MPI.SUM)

    def add_residual(self, b):
        if self.on:
            self.evaluation.add_residual(b)

    def add_tangent(self, A):
        if self.on:
            self.evaluation.add_tangent(A)

    # --- pairing and pattern -------------------------------------------------------
    def update_pairing(self, u, fresh):
        return self.geometry.update_pairing(u, fresh)

    def couplings(self):
        """Global dof pairs the contact adds to the matrix pattern (surfaces)."""
        extra = self.law.history.pattern_nodes() if self.law.frictional else None
        return self.geometry.couplings(extra)

    # --- monitor -----------------------------------------------------------------
    def _sum(self, values):
        return tuple(self.comm.allreduce(np.array(values, dtype=np.int64), op=MPI.SUM).tolist())

    def active_set_signature(self):
        """(number of active points and a checksum of who they are, all ranks): a
        change of the active set changes the signature."""
        if not self.on:
            return self._sum([0, 0])
        state = self.state
        active = self.geometry.active(state, self.augmented)
        if self.deformable:
            values = [len(active), int(active.sum() + state.facet[active].sum())]
            if self.frictional:
                values.append(int(np.count_nonzero(state.state == SLIP)))
            return self._sum(values)
        return self._sum([len(active), int(self.geometry.ids[active].sum())])

    def stick_slip_signature(self):
        """(sticking, slipping and checksums of both, all ranks); None without friction."""
        if not self.frictional:
            return None
        if not self.on:
            return self._sum([0, 0, 0, 0, 0])
        status = self.state.state
        ids = self.geometry.point_ids() if self.deformable else self.geometry.ids
        stick, slip = ids[status == STICK], ids[status == SLIP]
        return self._sum([len(stick), len(slip), stick.sum(), slip.sum(), (slip * slip).sum()])

    def point_status(self):
        """Per slave point of this rank: 0 open, 1 stick, 2 slip (a closed
        frictionless point slides: 2)."""
        status = np.zeros(len(self.geometry.point_area), np.int8)
        if not self.on:
            return status
        if self.frictional:
            return self.state.state.astype(np.int8)
        status[self.geometry.closed(self.state, self.augmented)] = 2
        return status

    def point_facets(self):
        """Per slave point of this rank: the master facet it is paired with, −1 where
        none (a rigid obstacle, a point off the master, the contact switched off)."""
        facets = np.full(len(self.geometry.point_area), -1, np.int32)
        if self.on and self.deformable:
            facets[:] = self.state.facet
        return facets

    def point_coordinates(self, u):
        """(reference, current) coordinates of this rank's slave points. Collective."""
        return self.geometry.point_coordinates(u)

    # --- augmented Lagrangian ------------------------------------------------------
    def max_penetration(self, u=None):
        """Largest penetration ⟨−g⟩ (all ranks), at u or at the prepared state."""
        if u is not None:
            self.prepare(u)
        return self.geometry.max_penetration(self.state) if self.on else 0.0

    def augment(self):
        if self.on:
            self.enforcement.augment(self.state)

    # --- steps ---------------------------------------------------------------------
    def commit(self):
        """The prepared (converged) evaluation becomes the history of the next
        step; switched off, the friction history and the multipliers are
        forgotten (the points start open when the pair is switched on)."""
        if self.on:
            self.law.commit(self.state, self.evaluation.x)
        else:
            self.law.forget(self.evaluation.x)
            self.enforcement.forget()
        self.enforcement.commit()

    def restore(self):
        """Back to the last converged step (a failed attempt)."""
        self.enforcement.restore()

    def state_dict(self):
        """(JSON-able metadata, this rank's arrays) of everything commit keeps."""
        law_meta, law_arrays = self.law.state_dict()
        enf_meta, enf_arrays = self.enforcement.state_dict()
        return {"law": law_meta, "enforcement": enf_meta}, {**law_arrays, **enf_arrays}

    def load_state_dict(self, meta, arrays):
        self.law.load_state_dict(meta["law"], arrays)
        self.enforcement.load_state_dict(meta["enforcement"], arrays)

    # --- results -------------------------------------------------------------------
    def observable_names(self):
        names = ["displacement", "fx", "fy", "fz", "closed_nodes", "area"]
        if self.frictional:
            names += ["dissipation_step", "dissipation", "stick_nodes", "slip_nodes", "stick_slip_flips"]
        return names

    def observables(self):
        """Scalars of the prepared evaluation and the committed history, all ranks:
        the obstacle's displacement, the force of the master on the slave body
        (normal and tangential), closed points, the loaded reference area, and with friction the
        dissipation (step, accumulated, N mm), stick/slip counts and flips."""
        force = self.force()  # zero switched off
        out = {"displacement": self.geometry.displacement(), "fx": float(force[0]), "fy": float(force[1]),
               "fz": float(force[2]), "closed_nodes": self.num_closed(), "area": self.contact_area()}
        out.update(self.law.observables())
        return out

    def point_fields(self):
        """(process-local node of each slave point, {field: per-point values})
        of the prepared evaluation — gap, pressure, status and, with friction,
        Coulomb.point_fields — or None when the points are not nodes."""
        nodes = self.geometry.field_nodes()
        if nodes is None:
            return None
        state = self.state
        fields = {"gap": state.gap, "pressure": state.pressure if self.on else np.zeros_like(state.pressure)}
        if self.frictional:
            fields.update(self.law.point_fields(self.geometry.point_area))
        else:
            status = np.zeros(len(nodes))
            status[self.geometry.closed(state, False)] = 2.0  # a closed frictionless point slides
            fields["status"] = status
        return nodes, fields
