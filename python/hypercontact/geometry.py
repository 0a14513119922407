"""Meshes with gmsh: built-in builders and mesh files.

Every mesh comes with named boundary surfaces (gmsh physical groups), which
scenes refer to by name (e.g. ``slave = "zmax"``, ``surface = "xmin"``).
"""
from dataclasses import dataclass
from pathlib import Path

import numpy as np
from . import _dolfinx as dfx


@dataclass
class Body:
    """A meshed body: dolfinx mesh, facet tags, and surface name → tag."""

    mesh: object
    facet_tags: object
    surfaces: dict


_gmsh_ready = False


def _gmsh():
    """gmsh, initialised once per process (gmsh 4.8 has no isInitialized)."""
    global _gmsh_ready
    import gmsh

    if not _gmsh_ready:
        gmsh.initialize(readConfigFiles=False)
        gmsh.option.setNumber("General.Terminal", 0)
        _gmsh_ready = True
    return gmsh


def _reset_gmsh():
    """Finalise gmsh after an error: a failed gmsh.open leaves state behind
    that makes later models mesh without volume elements."""
    global _gmsh_ready
    import gmsh

    gmsh.finalize()
    _gmsh_ready = False


def box_model(gmsh, size, n, m, origin=(0.0, 0.0, 0.0)):
    """Structured hexahedral box [origin, origin+size], n × n × m elements.

    Physical surfaces xmin, xmax, ymin, ymax, zmin, zmax; volume "body".
    n elements along x and y, m along z (through the thickness).
    """
    gmsh.model.add("box")
    x0, y0, z0 = origin
    lx, ly, lz = size
    gmsh.model.occ.addBox(x0, y0, z0, lx, ly, lz)
    gmsh.model.occ.synchronize()
    counts = {0: n, 1: n, 2: m}
    for _, tag in gmsh.model.getEntities(1):
        b = gmsh.model.getBoundingBox(1, tag)
        axis = int(np.argmax([b[3] - b[0], b[4] - b[1], b[5] - b[2]]))
        gmsh.model.mesh.setTransfiniteCurve(tag, counts[axis] + 1)
    for _, tag in gmsh.model.getEntities(2):
        gmsh.model.mesh.setTransfiniteSurface(tag)
        gmsh.model.mesh.setRecombine(2, tag)
    for _, tag in gmsh.model.getEntities(3):
        gmsh.model.mesh.setTransfiniteVolume(tag)
    lo = np.array(origin, dtype=float)
    tol = max(1e-5 * max(size), 1e-6)  # OCC bounding boxes are padded by ~1e-7 (absolute)
    names = {}
    for _, tag in gmsh.model.getEntities(2):
        b = np.array(gmsh.model.getBoundingBox(2, tag))
        for axis, a in enumerate("xyz"):
            if abs(b[axis] - b[axis + 3]) < tol:
                side = "min" if abs(b[axis] - lo[axis]) < tol else "max"
                names[f"{a}{side}"] = tag
    for i, (name, tag) in enumerate(sorted(names.items()), start=1):
        gmsh.model.addPhysicalGroup(2, [tag], i)
        gmsh.model.setPhysicalName(2, i, name)
    vol = gmsh.model.addPhysicalGroup(3, [e[1] for e in gmsh.model.getEntities(3)], 100)
    gmsh.model.setPhysicalName(3, vol, "body")
    gmsh.model.mesh.generate(3)


def _physical_surface_names(gmsh):
    return {gmsh.model.getPhysicalName(2, tag): tag for _, tag in gmsh.model.getPhysicalGroups(2)}


def build_box(comm, size, n, m, origin=(0.0, 0.0, 0.0)):
    """A structured hexahedral box body (see :func:`box_model`)."""
    return _from_gmsh(comm, lambda g: box_model(g, size, n, m, origin))


def read_msh(comm, path):
    """A body from a gmsh .msh file with named physical surfaces."""
    path = Path(path)
    if not path.is_file():
        raise FileNotFoundError(f"mesh file {str(path)!r} does not exist")

    def load(g):
        try:
            g.open(str(path))
        except Exception as err:  # gmsh raises a bare Exception
            raise ValueError(f"mesh file {str(path)!r} cannot be read by gmsh: {err}") from None
        if not g.model.getEntities(3):
            raise ValueError(f"mesh file {str(path)!r} has no volume (3D) elements")

    return _from_gmsh(comm, load)


def _from_gmsh(comm, make):
    gmsh = _gmsh() if comm.rank == 0 else None
    error, names = None, None
    if comm.rank == 0:
        gmsh.clear()
        try:
            make(gmsh)
            names = _physical_surface_names(gmsh)
        except Exception as err:
            error = err
    error = comm.bcast(error, root=0)
    if error is not None:
        if comm.rank == 0:
            _reset_gmsh()
        raise error
    names = comm.bcast(names, root=0)
    mesh, facet_tags = dfx.mesh_from_gmsh(gmsh.model if comm.rank == 0 else None, comm)
    if comm.rank == 0:
        gmsh.clear()
    return Body(mesh, facet_tags, names)

