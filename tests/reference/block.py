"""The 2 × 2 × 2 Mooney–Rivlin block between two frictionless rigid planes,
pressed by D: a scene in a homogeneous state (the closed form is in
homogeneous.py), shared by the tests that need a small, exactly known run."""
from mpi4py import MPI

from hypercontact import geometry

PARAMS = dict(alpha1=0.1863, alpha2=0.0098, K=5.0)
EPS = 50.0
D = 0.2


def write_block_msh(path):
    """The same 2 × 2 × 2 block written to a gmsh .msh file (rank 0)."""
    if MPI.COMM_WORLD.rank == 0:
        gmsh = geometry._gmsh()
        gmsh.clear()
        geometry.box_model(gmsh, [1.0, 1.0, 1.0], 2, 2)
        gmsh.write(str(path))
        gmsh.clear()
    MPI.COMM_WORLD.barrier()


def block_scene(out, i2="usual", law="mooney_rivlin", mesh_file=None):
    mesh = {"builder": "file", "file": str(mesh_file)} if mesh_file else {
        "builder": "box", "size": [1.0, 1.0, 1.0], "n": 2, "m": 2}
    return {
        "mesh": mesh,
        "material": {"law": law, "parameters": {**PARAMS, "i2": i2}},
        "bc": [{"surface": "xmin", "fix": ["x"]}, {"surface": "ymin", "fix": ["y"]}],
        "contact": [
            {"name": "top", "surface": "zmax", "obstacle": "plane", "point": [0, 0, 1.0],
             "normal": [0, 0, -1.0], "motion": [0, 0, -D], "eps_n": EPS},
            {"name": "base", "surface": "zmin", "obstacle": "plane", "point": [0, 0, 0],
             "normal": [0, 0, 1.0], "eps_n": EPS},
        ],
        "steps": {"initial": 0.25, "max": 0.5},
        "solver": {"rtol": 1e-12, "atol": 1e-12},
        "output": {"dir": str(out), "xdmf": False},
    }
