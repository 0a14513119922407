"""The fields of a run in ``fields.xdmf`` (ParaView), one frame per converged
step: ``displacement`` (vertex values), with contacts ``contact_gap`` and
``contact_pressure`` (zero off the contact surfaces), with friction the
:data:`FRICTION_FIELDS`, and cell-wise constant (DG0) fields at each cell's
midpoint: ``J`` = det F and, given the material's stress,
``cauchy_stress`` σ = J⁻¹ P Fᵀ and ``von_mises`` √(3/2 s:s). A field with a
NaN or an infinite value is never written: :class:`NonFiniteField` names it
and the step."""
import numpy as np
import ufl
from mpi4py import MPI

from .. import _dolfinx as dfx

#: Friction fields in fields.xdmf (when a contact has μ > 0): name → (key of
#: Coulomb.point_fields, whether a vector, description).
FRICTION_FIELDS = {
    "contact_status": ("status", False, "vertex values: 0 open or off the contact surfaces, 1 stick, 2 slip "
                       "(a closed node of a frictionless contact: 2)"),
    "contact_tangential_traction": ("traction", True, "vertex values, MPa: the tangential traction the "
                                    "obstacle exerts on the body"),
    "contact_tangential_traction_magnitude": ("traction", False, "vertex values, MPa: its magnitude (≤ μ × "
                                              "contact_pressure)"),
    "contact_slip_increment": ("slip_increment", True, "vertex values, mm: slip (the inelastic part of the "
                               "tangential motion) in this step"),
    "contact_accumulated_slip": ("accumulated_slip", False, "vertex values, mm: Σ |slip increment| over "
                                 "the steps so far"),
    "contact_dissipation_step": ("dissipation_step", False, "vertex values, N/mm (= mJ/mm²): frictional "
                                 "dissipation in this step per unit reference area (Σ nodal area × value = "
                                 "the contact's <name>_dissipation_step / symmetry factor)"),
    "contact_dissipation": ("dissipation", False, "vertex values, N/mm (= mJ/mm²): accumulated frictional "
                            "dissipation per unit reference area"),
}


class NonFiniteField(RuntimeError):
    """A field about to be written to fields.xdmf has NaN or infinite values."""


def first_piola_stress(psi, **params):
    """``stress(u)`` for :class:`ResultsWriter` from a law ψ(F, **params):
    P = ∂ψ/∂F by UFL at F = I + ∇u."""

    def stress(u):
        F = ufl.variable(ufl.Identity(len(u)) + ufl.grad(u))
        return ufl.diff(psi(F, **params), F)

    return stress


def von_mises(sigma):
    """√(3/2 s:s), s = σ − tr σ / 3 I, of an array of 3×3 tensors (n, 3, 3)."""
    s = sigma - np.trace(sigma, axis1=1, axis2=2)[:, None, None] / 3.0 * np.eye(3)
    return np.sqrt(1.5 * np.einsum("nij,nij->n", s, s))


class FieldWriter:
    """fields.xdmf of a run: ``u`` the solution's displacement (degree 2 in
    the mixed formulation: the cell fields are evaluated from it at the cell
    midpoints, written interpolated at the vertices), ``stress(u) -> P`` or
    None, ``frames_on_disk``: frames a resumed run finds already written."""

    def __init__(self, path, comm, u, contacts, stress, append, frames_on_disk):
        self.comm, self.u, self.contacts, self.stress, self.path = comm, u, contacts, stress, path
        self.frames_on_disk = frames_on_disk
        V = u.function_space
        self.u_out = u if V.ufl_element().degree() == 1 else dfx.fem.Function(dfx.vector_space(V.mesh, 1),
                                                                             name="displacement")
        if contacts:  # per node of V (any degree), written at the vertices
            self.Q, q_to_v = V.sub(0).collapse()
            self.q_nodes = np.asarray(q_to_v) // 3
            self.gap = dfx.fem.Function(self.Q, name="contact_gap")
            self.pressure = dfx.fem.Function(self.Q, name="contact_pressure")
        self.friction_fields = {}
        if any(c.frictional for c in contacts):
            self.friction_fields = {name: dfx.fem.Function(V if vector else self.Q, name=name)
                                    for name, (_, vector, _) in FRICTION_FIELDS.items()}
        self.xdmf = dfx.XDMFWriter(comm, path, V.mesh, append=append)
        # kernels compiled at the first step (FFCx JIT, timed as output)
        self._cell_kernels = None
        self._first_order = {}  # name → vertex-valued copy of a degree-2 contact field
        S = dfx.fem.FunctionSpace(V.mesh, ("DG", 0))
        self.J = dfx.fem.Function(S, name="J")
        if stress is not None:
            self.sigma = dfx.fem.Function(dfx.fem.TensorFunctionSpace(V.mesh, ("DG", 0)), name="cauchy_stress")
            self.von_mises = dfx.fem.Function(S, name="von_mises")

    def descriptions(self):
        """{field: what it holds} for summary.json."""
        out = {"displacement": "vertex values (Lagrange degree 1), mm"}
        if self.contacts:
            out["contact_gap"] = "vertex values, mm (0 off the contact surfaces)"
            out["contact_pressure"] = "vertex values, MPa (0 off the contact surfaces)"
        out.update({name: FRICTION_FIELDS[name][2] for name in self.friction_fields})
        out["J"] = "per cell (DG0, at the midpoint): det F"
        if self.stress is not None:
            out["cauchy_stress"] = "per cell (DG0, at the midpoint): σ = J⁻¹ P Fᵀ, 3×3 row by row, MPa"
            out["von_mises"] = "per cell (DG0, at the midpoint): √(3/2 s:s), s = dev σ, MPa"
        return out

    def compute(self, t, step):
        """The functions to write at this step, checked to be finite (None if a
        resumed run has this frame on disk already)."""
        if self.frames_on_disk > 0:
            return None
        if self.u_out is not self.u:
            self.u_out.interpolate(self.u)
        self._check_finite([self.u_out], t, step)  # first: the other fields are computed from it
        fields = [self._vertex_values(f) for f in self._contact_fields()] if self.contacts else []
        fields += self._cell_fields()
        self._check_finite(fields, t, step)
        return [self.u_out] + fields

    def write(self, t, fields):
        if self.frames_on_disk > 0:
            self.frames_on_disk -= 1
            return
        self.xdmf.write(fields, t)

    def close(self):
        self.xdmf.close()

    def _vertex_values(self, f):
        """f itself on first-order nodes; else its interpolant at the vertices
        (a Function of the same name, made once), as fields.xdmf holds them."""
        if f.function_space.ufl_element().degree() == 1:
            return f
        if f.name not in self._first_order:
            self._first_order[f.name] = dfx.first_order(f, f.function_space.mesh, f.name)
            self._first_order[f.name].name = f.name
        else:
            self._first_order[f.name].interpolate(f)
        return self._first_order[f.name]

    def _cell_kernels_compiled(self):
        """DG0 interpolation kernels of J and (with a stress law) σ = J⁻¹ P Fᵀ."""
        u = self.u
        F = ufl.Identity(len(u)) + ufl.grad(u)
        J = ufl.det(F)
        points = self.J.function_space.element.interpolation_points
        points = points() if callable(points) else points  # a method in dolfinx 0.5, a property later
        kernels = {"J": dfx.fem.Expression(J, points)}
        if self.stress is not None:
            P = self.stress(u)
            if not isinstance(P, ufl.core.expr.Expr) or P.ufl_shape != (3, 3):
                raise TypeError("ResultsWriter: stress(u) must return the first Piola–Kirchhoff stress as a "
                                f"3×3 UFL expression, returned {getattr(P, 'ufl_shape', type(P).__name__)}")
            kernels["cauchy_stress"] = dfx.fem.Expression(P * F.T / J, points)
        return kernels

    def _cell_fields(self):
        if self._cell_kernels is None:
            self._cell_kernels = self._cell_kernels_compiled()
        self.J.interpolate(self._cell_kernels["J"])
        if self.stress is None:
            return [self.J]
        self.sigma.interpolate(self._cell_kernels["cauchy_stress"])
        with np.errstate(invalid="ignore"):  # NaN in, NaN out: caught by the check
            self.von_mises.x.array[:] = von_mises(self.sigma.x.array.reshape(-1, 3, 3))
        return [self.sigma, self.von_mises, self.J]

    def _check_finite(self, functions, t, step):
        """Raise NonFiniteField naming every field with a NaN or an infinite value."""
        counts = []
        for f in functions:
            V = f.function_space
            owned = dfx.num_owned_nodes(V) * V.dofmap.index_map_bs
            counts.append([int(np.count_nonzero(~np.isfinite(f.x.array[:owned]))), owned])
        counts = np.array(counts, dtype=np.int64).reshape(-1, 2)
        self.comm.Allreduce(MPI.IN_PLACE, counts, op=MPI.SUM)
        bad = [f"'{f.name}' ({n} of {total} values)" for f, (n, total) in zip(functions, counts) if n]
        if bad:
            raise NonFiniteField(
                f"non-finite field{'s' if len(bad) > 1 else ''} {', '.join(bad)} at step {step} "
                f"(load factor {t:.6g}): NaN or infinite values, not written to {self.path}")

    def _contact_fields(self):
        """Vertex fields of the contacts' converged evaluation: gap (the last
        contact's where two share a node), pressure (summed), and the
        FRICTION_FIELDS (summed; the status: the larger), zero elsewhere."""
        n_local = dfx.num_local_nodes(self.u.function_space)
        values = {"gap": np.zeros(n_local), "pressure": np.zeros(n_local), "status": np.zeros(n_local),
                  "traction": np.zeros((n_local, 3)), "slip_increment": np.zeros((n_local, 3)),
                  "accumulated_slip": np.zeros(n_local), "dissipation_step": np.zeros(n_local),
                  "dissipation": np.zeros(n_local)}
        for c in self.contacts:
            fields = c.point_fields()
            if fields is None:  # Gauss-point contact: no value per node
                continue
            nodes, per_point = fields
            for key, v in per_point.items():
                if key == "gap":
                    values[key][nodes] = v
                elif key == "status":
                    values[key][nodes] = np.maximum(values[key][nodes], v)
                else:
                    values[key][nodes] += v
        self.gap.x.array[:] = values["gap"][self.q_nodes]
        self.pressure.x.array[:] = values["pressure"][self.q_nodes]
        dfx.update_ghosts(self.gap)
        dfx.update_ghosts(self.pressure)
        return [self.gap, self.pressure] + self._friction_fields(values)

    def _friction_fields(self, values):
        """The FRICTION_FIELDS functions filled from the per-node ``values``."""
        if not self.friction_fields:
            return []
        out = []
        for name, f in self.friction_fields.items():
            key, vector, _ = FRICTION_FIELDS[name]
            v = values[key]
            if vector:
                f.x.array[:] = v.ravel()
            elif v.ndim == 2:  # the magnitude of a vector
                f.x.array[:] = np.linalg.norm(v, axis=1)[self.q_nodes]
            else:
                f.x.array[:] = v[self.q_nodes]
            dfx.update_ghosts(f)
            out.append(f)
        return out

