"""Several physical volumes of one gmsh file are several bodies, each with
its own material: a [[body]] with ``volume = "<name>"`` claims one, the
scene's [material] is that of the others.

A bar of two bonded parts (two physical volumes sharing their face, meshed
together) stretched or compressed by a prescribed displacement, its lateral
faces on rollers: each part is in a homogeneous uniaxial strain F = diag(1, 1,
λ_i), exact in Q1, and both carry the same nominal stress, so the closed form
is two finite-strain springs in series, solved here from the principal-stretch
energy (reference/homogeneous.py), independently of the UFL forms. (Free
lateral faces would not do: bonded parts of different stiffness contract
sideways differently, and the interface makes the state inhomogeneous.)
Two volumes meshed apart in one file (a seal and its housing) are bodies in
contact: the stacked blocks of reference/stack.py, one of each material."""
import numpy as np
import pytest
from conftest import quiet
from mpi4py import MPI
from scipy.optimize import fsolve

from hypercontact import _dolfinx as dfx
from hypercontact import geometry, scene
from hypercontact.simulation import Simulation
from reference.homogeneous import neo_hookean_principal, nominal_stress
from reference.stack import write_stack_msh

SOFT = {"law": "neo_hookean", "parameters": {"mu": 1.0, "K": 3.0}}
STIFF = {"law": "neo_hookean", "parameters": {"mu": 5.0, "K": 15.0}}
LOWER, UPPER = 0.4, 0.6  # the parts' lengths along z (cross-section 1 × 1)


def write_bar_msh(path, orphan=False, overlap=False):
    """[0,1]² × [0, LOWER] and [0,1]² × [LOWER, 1], fragmented (one shared face), 2 × 2 hexahedra across and
    0.2 along z, to ``path`` (rank 0). Physical volumes "lower" and "upper"; surfaces xmin ... zmax.
    ``orphan``: the upper part in no physical volume (saved all the same); ``overlap``: both parts in a third
    physical volume "all" too."""
    if MPI.COMM_WORLD.rank == 0:
        gmsh = geometry._gmsh()
        gmsh.clear()
        gmsh.model.add("bar")
        a = gmsh.model.occ.addBox(0, 0, 0, 1, 1, LOWER)
        b = gmsh.model.occ.addBox(0, 0, LOWER, 1, 1, UPPER)
        gmsh.model.occ.fragment([(3, a)], [(3, b)])
        gmsh.model.occ.synchronize()
        for _, tag in gmsh.model.getEntities(1):
            lo_hi = np.array(gmsh.model.getBoundingBox(1, tag)).reshape(2, 3)
            length = np.ptp(lo_hi, axis=0)
            gmsh.model.mesh.setTransfiniteCurve(tag, (round(length[2] / 0.2) if length[2] > 1e-6 else 2) + 1)
        for _, tag in gmsh.model.getEntities(2):
            gmsh.model.mesh.setTransfiniteSurface(tag)
            gmsh.model.mesh.setRecombine(2, tag)
        parts = sorted((gmsh.model.getBoundingBox(3, t)[2], t) for _, t in gmsh.model.getEntities(3))
        for _, tag in parts:
            gmsh.model.mesh.setTransfiniteVolume(tag)
        names = {}
        for _, tag in gmsh.model.getEntities(2):
            lo, hi = np.array(gmsh.model.getBoundingBox(2, tag)).reshape(2, 3)
            for axis in range(3):
                if hi[axis] - lo[axis] < 1e-6 and (lo[axis] < 1e-6 or lo[axis] > 1 - 1e-6):
                    names.setdefault("xyz"[axis] + ("min" if lo[axis] < 1e-6 else "max"), []).append(tag)
        for i, (name, tags) in enumerate(sorted(names.items()), start=1):
            gmsh.model.addPhysicalGroup(2, tags, i)
            gmsh.model.setPhysicalName(2, i, name)
        for i, (name, (_, tag)) in enumerate(zip(("lower", "upper"), parts[: 1 if orphan else 2]), start=100):
            gmsh.model.addPhysicalGroup(3, [tag], i)
            gmsh.model.setPhysicalName(3, i, name)
        if overlap:
            gmsh.model.addPhysicalGroup(3, [t for _, t in parts], 200)
            gmsh.model.setPhysicalName(3, 200, "all")
        gmsh.option.setNumber("Mesh.SaveAll", 1 if orphan else 0)
        gmsh.model.mesh.generate(3)
        gmsh.write(str(path))
        gmsh.option.setNumber("Mesh.SaveAll", 0)
        gmsh.clear()
    MPI.COMM_WORLD.barrier()


def two_springs(lower, upper, d, lengths=(LOWER, UPPER), compliance=0.0):
    """(λ_lower, λ_upper, P33) of the bar stretched by d (uniaxial strain in each part, one nominal stress);
    ``compliance``: of penalty gaps in series (gaps of −P33 × it)."""
    def stress(material, stretch):
        return nominal_stress(lambda a, b, c: neo_hookean_principal(a, b, c, **material["parameters"]),
                              (1.0, 1.0, stretch), 2)

    def equations(z):
        la, lb = z
        P = stress(lower, la)
        return [P - stress(upper, lb), la * lengths[0] + lb * lengths[1] + P * compliance - (sum(lengths) + d)]

    la, lb = fsolve(equations, [1.0 + d, 1.0 + d], xtol=1e-13)
    assert np.max(np.abs(equations([la, lb]))) < 1e-13
    return la, lb, stress(lower, la)


def bar_scene(msh, out_dir, material, bodies, d):
    rollers = [{"surface": f"{a}{side}", "fix": [a]} for a in "xy" for side in ("min", "max")]
    return {
        "mesh": {"builder": "file", "file": str(msh)},
        "material": material,
        "body": bodies,
        "bc": rollers + [{"surface": "zmin", "fix": ["z"]},
                         {"surface": "zmax", "fix": ["z"], "motion": [0.0, 0.0, d]}],
        "steps": {"initial": 0.5, "max": 0.5},
        "solver": {"rtol": 1e-12, "atol": 1e-12},
        "output": {"dir": str(out_dir), "xdmf": False},
    }


def force_and_uz(sim):
    """(z-force on zmax: the internal-force residual summed over its nodes, all ranks; (owned node
    coordinates, their u_z))."""
    b = dfx.assemble_vector_owned(sim.problem.R)
    with b.localForm() as bl:
        r = bl.array_r.copy()
    b.destroy()
    n = dfx.num_owned_nodes(sim.V)
    X = dfx.node_coordinates(sim.V)[:n]
    rz = np.array([r[sim.unknown_dof(i, 2)] for i in range(n)])
    uz = sim.u.x.array.reshape(-1, 3)[:n, 2]
    return sim.comm.allreduce(rz[np.isclose(X[:, 2], 1.0)].sum()), X, uz


def run_bar(msh, out_dir, lower, upper, d, comm=MPI.COMM_WORLD):
    """The bar with ``lower`` claimed by a [[body]] ("insert", volume "lower") and ``upper`` the scene's
    [material] (the unclaimed volume)."""
    bodies = [{"name": "insert", "volume": "lower", "material": lower}]
    sim = Simulation(scene.load(bar_scene(msh, out_dir, upper, bodies, d)), comm, log=quiet)
    sim.run()
    return sim


@pytest.mark.parametrize("d", [0.1, -0.1])
@pytest.mark.parametrize("lower, upper", [(SOFT, STIFF), (STIFF, SOFT)], ids=["soft-lower", "stiff-lower"])
def test_bonded_bar_is_two_springs_in_series(lower, upper, d, out_dir):
    """Force and each part's stretch equal the closed form to 1e-10 (both exact in Q1: only Newton's
    tolerance is left); the swapped materials' force differs from the closed form of the unswapped ones
    by far more than that, so materials on the wrong volumes fail."""
    msh = out_dir / "bar.msh"
    write_bar_msh(msh)
    force, X, uz = force_and_uz(run_bar(msh, out_dir, lower, upper, d))
    la, lb, P33 = two_springs(lower, upper, d)
    assert force == pytest.approx(P33, rel=1e-10)
    # each part's stretch: u_z is λ_lower Z below the interface, then grows by λ_upper per unit length
    expected = np.where(X[:, 2] <= LOWER, (la - 1.0) * X[:, 2], (la - 1.0) * LOWER + (lb - 1.0) * (X[:, 2] - LOWER))
    np.testing.assert_allclose(uz, expected, rtol=0, atol=1e-12)
    _, _, swapped = two_springs(upper, lower, d)
    assert abs(swapped - P33) > 0.1 * abs(P33)


def test_run_header_names_each_volume_and_its_material(out_dir):
    """The header lists the file's volumes with their laws and parameters, whatever the body is named."""
    msh = out_dir / "bar.msh"
    write_bar_msh(msh)
    sc = scene.load(bar_scene(msh, out_dir, SOFT, [{"name": "insert", "volume": "upper", "material": STIFF}], 0.1))
    sim = Simulation(sc, MPI.COMM_WORLD, log=quiet)
    assert sim.effects[0] == "2 bodies (lower: neo_hookean [mu = 1, K = 3]; upper: neo_hookean [mu = 5, K = 15])"


def test_a_volume_the_file_has_not_is_refused_naming_the_file_and_its_volumes(out_dir):
    msh = out_dir / "bar.msh"
    write_bar_msh(msh)
    with pytest.raises(scene.SceneError, match=r"scene key 'body\[0\]\.volume': mesh file '.*bar\.msh' has no "
                                               r"physical volume 'uper' \(it has lower, upper\); did you mean "
                                               r"'upper'\?"):
        Simulation(scene.load(bar_scene(msh, out_dir, SOFT, [{"name": "insert", "volume": "uper", "material": STIFF}],
                                        0.1)), MPI.COMM_WORLD, log=quiet)


@pytest.mark.parametrize("kind, words", [
    ("orphan", r"the elements of volume \d+ are in no physical volume \(its physical volumes: lower\)"),
    ("overlap", r"volume \d+ is in the physical volumes '(lower|upper)' and 'all': a cell can be in one only"),
])
def test_cells_in_no_or_two_physical_volumes_are_refused(kind, words, out_dir):
    """dolfinx reads the cells of physical volumes only (a volume in none would lose its cells), once per
    physical volume (in two: its cells twice)."""
    msh = out_dir / f"{kind}.msh"
    write_bar_msh(msh, orphan=kind == "orphan", overlap=kind == "overlap")
    with pytest.raises(ValueError, match=f"mesh file '.*{kind}\\.msh'.*{words}"):
        geometry.read_msh(MPI.COMM_WORLD, msh)


def test_volumes_meshed_apart_are_bodies_in_contact(out_dir):
    """The upper block (volume "upper", body "seal", stiff) pressed onto the lower ([material], soft)
    between rigid planes, lateral faces on rollers (free ones would slide the blocks' matching facets apart,
    and node-to-surface contact would no longer pass the patch test): each block in its own homogeneous
    uniaxial strain, two springs and three penalty gaps in series. The slave surface's material (for the
    automatic penalty) is that of the volume it bounds."""
    msh = out_dir / "stack.msh"
    write_stack_msh(msh, volumes=("lower", "upper"))
    eps, d = 50.0, 0.1
    plane = {"obstacle": "plane", "eps_n": eps}
    data = {
        "mesh": {"builder": "file", "file": str(msh)},
        "material": SOFT,
        "body": [{"name": "seal", "volume": "upper", "material": STIFF}],
        "bc": [{"surface": f"{a}{side}", "fix": [a]} for a in "xy" for side in ("min", "max")],
        "contact": [
            {"name": "top", "surface": "top", **plane, "point": [0, 0, 1.0], "normal": [0, 0, -1.0],
             "motion": [0, 0, -d]},
            {"name": "base", "surface": "base", **plane, "point": [0, 0, 0], "normal": [0, 0, 1.0]},
            {"name": "interface", "surface": "upper_bottom", "obstacle": "surface", "master": "lower_top",
             "eps_n": eps},
        ],
        "steps": {"initial": 0.25, "max": 0.5},
        "solver": {"rtol": 1e-12, "atol": 1e-12},
        "output": {"dir": str(out_dir), "xdmf": False},
    }
    sim = Simulation(scene.load(data), MPI.COMM_WORLD, log=quiet)
    assert [sim.material_of(name)["parameters"]["mu"] for name in ("upper_bottom", "lower_top")] == [5.0, 1.0]
    with pytest.raises(scene.SceneError, match="surface 'xmin' bounds the physical volumes lower, upper"):
        sim.material_of("xmin")
    sim.run()
    la, lb, P3 = two_springs(SOFT, STIFF, -d, (0.5, 0.5), 3 / eps)
    top, base, interface = sim.contacts
    assert top.force(sim.u)[2] == pytest.approx(P3, rel=1e-8)
    assert interface.force(sim.u)[2] == pytest.approx(-P3, rel=1e-8)
    X = sim.V.tabulate_dof_coordinates()[: sim.V.dofmap.index_map.size_local]
    uz = sim.u.x.array.reshape(-1, 3)[: len(X), 2]
    for z, expected in ((1.0, -d - P3 / eps), (0.0, P3 / eps)):  # the top and the base penetrate by -P3 / ε
        np.testing.assert_allclose(uz[np.isclose(X[:, 2], z)], expected, rtol=0, atol=1e-10)
    # at z = ½ the soft block's top, then (the interface's gap on) the stiff block's bottom: swapped
    # materials give the same force (equal heights) but not these
    lower_top = P3 / eps + (la - 1.0) * 0.5
    assert abs(lower_top - (P3 / eps + (lb - 1.0) * 0.5)) > 1e-2
    mid = uz[np.isclose(X[:, 2], 0.5)]
    assert np.all(np.min(np.abs(mid[:, None] - [lower_top, lower_top + P3 / eps]), axis=1) < 1e-10)


@pytest.mark.mpi
def test_two_ranks_give_the_serial_force(out_dir, tmp_path):
    """The bonded bar on the ranks of COMM_WORLD (gmsh reads on rank 0, the cells' volumes travel with
    them) equals a serial run and the closed form."""
    comm = MPI.COMM_WORLD
    if comm.size < 2:
        pytest.skip("needs mpirun -n 2")
    msh = out_dir / "bar.msh"
    write_bar_msh(msh)
    f_par, _, _ = force_and_uz(run_bar(msh, out_dir, SOFT, STIFF, -0.1))
    f_ser, _, _ = force_and_uz(run_bar(msh, tmp_path / "serial", SOFT, STIFF, -0.1, MPI.COMM_SELF))
    assert f_par == pytest.approx(f_ser, rel=1e-10)
    assert f_par == pytest.approx(two_springs(SOFT, STIFF, -0.1)[2], rel=1e-10)
