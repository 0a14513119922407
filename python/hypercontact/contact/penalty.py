"""Automatic, unit-free penalty parameters.

    ε_N = s · M / h,

with s the scene's dimensionless ``penalty_factor``, M = E/(1 − ν²) =
4μ (3K + μ)/(3K + 4μ) the small-strain indentation (plane-strain) modulus of
the slave body's material — the modulus of Hertz's and Boussinesq's
solutions, how stiff a body is to a pressure on a part of its surface — and
h = Σ V_e / Σ A_f the thickness of the layer of elements under the slave
surface (the volume of the cells that touch the slave facets over the
facets' area, reference configuration). The penalty pressure ε_N g for a
penetration g then equals s × the pressure that indents the surface by g
over a patch of size h: with s = 100 the penetration is about 1 % of the
body's own deflection under the contact pressure. Both M and h scale with
the units (MPa and mm, or Pa and m), so the same scene in either gives the
same dimensionless results.

Why not the P-wave modulus K + 4/3 μ (the stiffness of a laterally confined
column, used before): for nearly incompressible rubber (K/μ = 10³) it is
~K, about 250 times the ~4μ with which the body actually gives way under a
contact pressure, and so a penalty 250 times stiffer than the factor says. Newton then chatters
(an O-ring of P2–P1 tetrahedra at K/μ = 10³: Δλ cut to 6e-4 and 10–40
iterations per step, docs/verification.md §13). The two agree at ν = 0
(2μ) and differ by 1.2× at ν = 0.3; only a thin layer confined under a
broad contact is stiffer than E*, by up to (K + 4/3 μ)/E*: there the
penetration's share grows by that factor (penalty_factor is the knob).

The tangential penalty of Coulomb friction, when the scene leaves ``eps_t``
at 0, is

    ε_T = min(10 · G / h, ε_N),

G the slave body's small-strain shear modulus and h the same layer
thickness: the shear stiffness of that layer over a tenth of its thickness.
A sticking point then moves elastically by μ p_N / ε_T = h · μ p_N / (10 G),
3 % of the first layer for rubber pressed to p_N ≈ G at μ = 0.3, falling
with h under refinement. With ε_T = ε_N (about 400 G/h for rubber, the
default before) the band in which a point sticks, 2 μ p_N / ε_T wide, is
narrower than the tangential part of a Newton correction and the stick/slip
status chatters: the O-ring of P2–P1 tetrahedra took 178 load steps
instead of 4 (docs/robustness.md §2, which measures what each choice costs).
"""
import numpy as np
import ufl
from mpi4py import MPI

from .. import _dolfinx as dfx
from ..forms.registry import LAWS


def small_strain_moduli(law, params):
    """(K, μ0) of a built-in law at small strain, μ0 from the law registry
    (every volumetric energy, materials.VOLUMETRIC, has Ψ0''(1) = K)."""
    if law not in LAWS:
        raise ValueError(f"automatic penalty: no small-strain modulus for law {law!r}")
    mu, _ = LAWS[law].shear_modulus(LAWS[law].with_defaults(params))
    return float(params["K"]), float(mu)


def indentation_modulus(law, params):
    """E* = E/(1 − ν²) = 4μ (3K + μ)/(3K + 4μ) at small strain; 4μ for K = ∞."""
    K, mu = small_strain_moduli(law, params)
    if K == float("inf"):
        return 4.0 * mu
    return 4.0 * mu * (3.0 * K + mu) / (3.0 * K + 4.0 * mu)


def layer_thickness(V, facet_tags, tag):
    """h = Σ V_e / Σ A_f over the slave facets with tag and their cells."""
    mesh = V.mesh
    facets = dfx.facets_with_tag(facet_tags, tag)
    n_owned = dfx.num_owned_cells(mesh)
    cells = np.unique(dfx.facet_cells(mesh, facets)).astype(np.int32)
    cells = cells[cells < n_owned]
    DG0 = dfx.fem.FunctionSpace(mesh, ("DG", 0))
    vol = dfx.assemble_vector_owned(dfx.compile_form(ufl.TestFunction(DG0) * ufl.dx))
    with vol.localForm() as vl:
        volume = float(vl.array_r[cells].sum())
    vol.destroy()
    one = dfx.constant(mesh, 1.0)
    ds = dfx.facet_integration_measure(mesh, facet_tags, 2)
    area = dfx.assemble_scalar(dfx.compile_form(one * ds(tag)), mesh.comm)
    volume = mesh.comm.allreduce(volume, op=MPI.SUM)
    if not area > 0:
        raise ValueError("automatic penalty: the slave surface has no area")
    return volume / area


def smoothing_band(spec, V, facet_tags, tags):
    """The band δ = smoothing × h of the smoothed normal law (C++ penetration.hpp), h the
    thinnest first element layer under the slave surfaces ``tags``; 0 when the contact's
    ``smoothing`` is 0 (the paper's sharp ⟨−g⟩)."""
    factor = float(spec.get("smoothing", 0.0))
    if factor == 0.0:
        return 0.0
    return factor * min(layer_thickness(V, facet_tags, t) for t in tags)


def automatic_penalty(factor, law, params, V, facet_tags, tag):
    """(ε_N, M, h) for a slave surface (see the module docstring)."""
    M = indentation_modulus(law, params)
    h = layer_thickness(V, facet_tags, tag)
    return factor * M / h, M, h


#: ε_T = TANGENTIAL_FACTOR × G / h when a frictional contact leaves eps_t at 0 (see the module docstring)
TANGENTIAL_FACTOR = 10.0


def automatic_tangential_penalty(law, params, V, facet_tags, tag):
    """(10 G / h, G, h) for a slave surface (see the module docstring; the caller caps it at ε_N)."""
    _, G = small_strain_moduli(law, params)
    h = layer_thickness(V, facet_tags, tag)
    return TANGENTIAL_FACTOR * G / h, G, h
