"""Two blocks stacked between two frictionless rigid planes, meshed apart
(coincident faces, separate nodes) as one gmsh .msh file — tetrahedra or
hexahedra, first or second order — with the lower block's top the master of
the upper block's bottom. Homogeneous uniaxial compression: the closed form
of homogeneous.py with three penalty gaps (base, interface, top) instead of
two: λ3 L + 2 P3/ε + P3/ε_i = L − d."""
import numpy as np
from mpi4py import MPI
from scipy.optimize import fsolve

from hypercontact import geometry
from reference.homogeneous import nominal_stress


def write_stack_msh(path, n=2, m=1, cells="tetrahedra", order=1, volumes=("body",)):
    """[0,1]² × [0,½] and [0,1]² × [½,1], n × n × m cells each, to ``path`` (rank 0).
    Physical surfaces: base, lower_top, upper_bottom, top, xmin, ymin, xmax, ymax; volume "body"
    (``volumes``: one name, both blocks; two names, the lower and the upper block)."""
    if MPI.COMM_WORLD.rank == 0:
        gmsh = geometry._gmsh()
        gmsh.clear()
        gmsh.model.add("stack")
        boxes = [gmsh.model.occ.addBox(0, 0, 0, 1, 1, 0.5), gmsh.model.occ.addBox(0, 0, 0.5, 1, 1, 0.5)]
        gmsh.model.occ.synchronize()
        for _, tag in gmsh.model.getEntities(1):
            b = gmsh.model.getBoundingBox(1, tag)
            vertical = b[5] - b[2] > max(b[3] - b[0], b[4] - b[1])
            gmsh.model.mesh.setTransfiniteCurve(tag, (m if vertical else n) + 1)
        for _, tag in gmsh.model.getEntities(2):
            gmsh.model.mesh.setTransfiniteSurface(tag)
            if cells == "hexahedra":
                gmsh.model.mesh.setRecombine(2, tag)
        for _, tag in gmsh.model.getEntities(3):
            gmsh.model.mesh.setTransfiniteVolume(tag)
        names = {"base": [], "lower_top": [], "upper_bottom": [], "top": [], "xmin": [], "ymin": [], "xmax": [],
                 "ymax": []}
        for vol, box in enumerate(boxes):
            for dim, tag in gmsh.model.getBoundary([(3, box)], oriented=False):
                b = np.array(gmsh.model.getBoundingBox(2, tag))
                lo, hi = b[:3], b[3:]
                if hi[2] - lo[2] < 1e-6:
                    z = lo[2]
                    names[("base" if z < 0.25 else "lower_top") if vol == 0 else
                          ("upper_bottom" if z < 0.75 else "top")].append(tag)
                elif hi[0] - lo[0] < 1e-6 and lo[0] < 1e-6:
                    names["xmin"].append(tag)
                elif hi[1] - lo[1] < 1e-6 and lo[1] < 1e-6:
                    names["ymin"].append(tag)
                else:
                    names["xmax" if hi[0] - lo[0] < 1e-6 else "ymax"].append(tag)
        for i, (name, tags) in enumerate(names.items(), start=1):
            gmsh.model.addPhysicalGroup(2, tags, i)
            gmsh.model.setPhysicalName(2, i, name)
        for k, (name, tags) in enumerate(zip(volumes, [boxes] if len(volumes) == 1 else [[b] for b in boxes])):
            gmsh.model.addPhysicalGroup(3, tags, 100 + k)
            gmsh.model.setPhysicalName(3, 100 + k, name)
        gmsh.option.setNumber("Mesh.ElementOrder", order)
        gmsh.model.mesh.generate(3)
        gmsh.write(str(path))
        gmsh.clear()
    MPI.COMM_WORLD.barrier()


def stacked_block(psi, L, d, eps, interface_eps=None):
    """(λ_lateral, λ3, P3) of the stack pressed by d: the planes' gaps P3/ε each and the
    interface's P3/ε_i (ε_i = ε; two-pass contact on matching meshes: 2ε, both passes press)."""
    eps_i = eps if interface_eps is None else interface_eps

    def equations(z):
        lat, l3 = z
        s = (lat, lat, l3)
        P3 = nominal_stress(psi, s, 2)
        return [nominal_stress(psi, s, 0), l3 * L + 2 * P3 / eps + P3 / eps_i - (L - d)]

    lat, l3 = fsolve(equations, [1.0, 1.0 - d / L], xtol=1e-13)
    assert np.max(np.abs(equations([lat, l3]))) < 1e-13
    return lat, l3, nominal_stress(psi, (lat, lat, l3), 2)
