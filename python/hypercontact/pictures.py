"""Pictures of a run, drawn headless (matplotlib's Agg backend).

- :func:`load_curves`: columns of a run's ``curves.csv`` against one another
  (e.g. the punch force against the indentation, the inner pressure of the
  sphere against the equator's displacement).
- :func:`deformed_shape`: the deformed boundary surface of the body,
  coloured by a nodal or a cell field. Collective in parallel: every rank
  passes its part, rank 0 draws.

:class:`~hypercontact.results.ResultsWriter` draws ``curves.png`` and
``deformed.png`` with these at the end of every run that converged at least
one step.
"""
import csv
import json
from pathlib import Path

import matplotlib

matplotlib.use("Agg")  # headless: never needs a display
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from mpl_toolkits.mplot3d.art3d import Poly3DCollection  # noqa: E402

from . import _dolfinx as dfx  # noqa: E402

#: Vertices of dolfinx's reference quadrilateral (0,0), (1,0), (0,1), (1,1)
#: in the order that walks around its boundary.
QUAD_CYCLE = [0, 1, 3, 2]


def _read_csv(csv_path):
    with open(csv_path, newline="") as f:
        rows = list(csv.reader(f))
    if not rows:
        raise ValueError(f"{csv_path}: empty file (no header)")
    header, body = rows[0], rows[1:]
    if not body:
        raise ValueError(f"{csv_path}: no rows (no converged step)")
    data = np.array([[float(v) for v in row] for row in body], dtype=float)
    return header, data


def _scene_title(folder):
    """The scene's title from the summary.json beside a results file, or ''."""
    try:
        return json.loads((Path(folder) / "summary.json").read_text())["scene"].get("title", "") or ""
    except (OSError, ValueError, KeyError, AttributeError):
        return ""


def load_curves(csv_path, png_path, x, ys, labels=None, title=None):
    """Draw the columns ``ys`` of a run's curves.csv against the column ``x``
    into ``png_path``. Axes are labelled with the column names, the legend
    with ``labels`` (default: the column names); the title is the scene's
    (from the summary.json beside the csv; ``title`` overrides). A curve
    with a single row is drawn as a point. Returns ``png_path``."""
    csv_path, png_path = Path(csv_path), Path(png_path)
    ys = [ys] if isinstance(ys, str) else list(ys)
    labels = list(ys) if labels is None else list(labels)
    if len(labels) != len(ys):
        raise ValueError(f"load_curves: {len(ys)} columns but {len(labels)} labels")
    header, data = _read_csv(csv_path)
    missing = [c for c in [x, *ys] if c not in header]
    if missing:
        raise KeyError(f"{csv_path}: no column {', '.join(map(repr, missing))} "
                       f"(columns: {', '.join(header)})")
    if title is None:
        title = _scene_title(csv_path.parent) or csv_path.parent.name
    X = data[:, header.index(x)]
    fig, ax = plt.subplots(figsize=(7.0, 4.8), dpi=110)
    try:
        for column, label in zip(ys, labels):
            ax.plot(X, data[:, header.index(column)], marker="o", markersize=3.5, linewidth=1.5, label=label)
        ax.set_xlabel(x)
        ax.set_ylabel(ys[0] if len(ys) == 1 else ", ".join(ys))
        ax.set_title(title, fontsize=10)
        ax.grid(True, alpha=0.3)
        ax.axhline(0.0, color="0.5", linewidth=0.6)
        if len(ys) > 1 or labels != ys:
            ax.legend()
        fig.tight_layout()
        fig.savefig(png_path, bbox_inches="tight", pad_inches=0.15)
    finally:
        plt.close(fig)
    return png_path


def _local_surface(mesh, u, values, scale):
    """This rank's owned exterior facets: (polygons (n, 4, 3) in the deformed
    configuration, one colour value per facet, label)."""
    nodes, cells = dfx.owned_exterior_facets(mesh)
    if nodes.shape[1] != 4:
        raise ValueError(f"deformed_shape: needs quadrilateral boundary facets (hexahedra), "
                         f"found {nodes.shape[1]} nodes per facet")
    nodes = nodes[:, QUAD_CYCLE]

    u1 = dfx.first_order(u, mesh, "u")
    g2d = dfx.geometry_to_dofs(mesh, u1.function_space)
    U = u1.x.array.reshape(-1, 3)[g2d]
    X = mesh.geometry.x[:, :3] + scale * U
    polygons = X[nodes]

    label = None
    if values is None or isinstance(values, str):
        key = values or "magnitude"
        comps = {"ux": 0, "uy": 1, "uz": 2}
        if key == "magnitude":
            nodal, label = np.linalg.norm(U, axis=1), "|u|"
        elif key in comps:
            nodal, label = U[:, comps[key]], key
        else:
            raise ValueError(f"deformed_shape: values must be a Function, 'magnitude', 'ux', 'uy' or 'uz', "
                             f"found {values!r}")
        colour = nodal[nodes].mean(axis=1)
    else:
        label = values.name
        element = values.function_space.ufl_element()
        if element.degree() == 0:  # one value per cell: the cell of each exterior facet
            if values.ufl_shape != ():
                raise ValueError(f"deformed_shape: the cell field {values.name!r} must be scalar")
            colour = values.x.array[dfx.cell_dofs(values.function_space, cells)]
        else:
            v1 = dfx.first_order(values, mesh, values.name)
            w = v1.x.array.reshape(-1, int(np.prod(values.ufl_shape, dtype=int)))
            w = w[dfx.geometry_to_dofs(mesh, v1.function_space)]
            nodal = w[:, 0] if w.shape[1] == 1 else np.linalg.norm(w, axis=1)
            if w.shape[1] > 1:
                label = f"|{label}|"
            colour = nodal[nodes].mean(axis=1)
    return polygons, np.asarray(colour, dtype=float), label


def deformed_shape(mesh, u, values, png_path, scale=1.0, title="", label=None, view=(28.0, -130.0),
                   cmap="viridis", limits=None):
    """Draw the boundary surface of the body deformed by ``u`` (times
    ``scale``) into ``png_path``, each boundary facet coloured by ``values``:

    - ``None`` or ``"magnitude"``: |u| (nodal); ``"ux"``, ``"uy"``, ``"uz"``: a component;
    - a scalar dolfinx Function: nodal if Lagrange (any degree: interpolated
      at the vertices), per cell if DG0 (the value of the facet's cell);
    - a vector Lagrange Function: its magnitude.

    Nodal fields colour a facet by the mean of its vertices. Collective: call
    on every rank; rank 0 gathers the owned exterior facets and draws. A
    failure on any rank raises the same RuntimeError on every rank. Returns
    ``png_path``. ``view`` = (elevation, azimuth) in degrees. ``limits`` =
    (low, high) fixes the colour scale (values outside take the end colours),
    e.g. to compare pictures of several runs; default: the field's range."""
    comm = mesh.comm
    try:
        local = _local_surface(mesh, u, values, scale)
        error = None
    except Exception as err:  # reported collectively below, so no rank waits forever
        local, error = None, f"{type(err).__name__}: {err}"
    gathered = comm.gather((local, error), root=0)
    outcome = None
    if comm.rank == 0:
        errors = [f"rank {r}: {e}" for r, (_, e) in enumerate(gathered) if e is not None]
        if errors:
            outcome = "; ".join(errors)
        else:
            try:
                polygons = np.concatenate([p for (p, _, _), _ in gathered], axis=0)
                colour = np.concatenate([c for (_, c, _), _ in gathered])
                _draw_surface(polygons, colour, png_path, title, label or gathered[0][0][2], view, cmap, limits)
            except Exception as err:
                outcome = f"{type(err).__name__}: {err}"
    outcome = comm.bcast(outcome, root=0)
    if outcome is not None:
        raise RuntimeError(f"deformed_shape: {outcome}")
    return Path(png_path)


def _draw_surface(polygons, colour, png_path, title, label, view, cmap, limits=None):
    if len(polygons) == 0:
        raise ValueError("no exterior facets")
    if not np.all(np.isfinite(polygons)) or not np.all(np.isfinite(colour)):
        raise ValueError("non-finite coordinates or values")
    if limits is not None and not (len(limits) == 2 and np.all(np.isfinite(limits)) and limits[0] < limits[1]):
        raise ValueError(f"limits must be two finite numbers (low, high) with low < high, found {limits!r}")
    lo, hi = (float(colour.min()), float(colour.max())) if limits is None else (float(limits[0]), float(limits[1]))
    if hi - lo <= 1e-12 * max(abs(lo), abs(hi), 1e-300):  # a constant field: a visible, centred range
        pad = max(abs(lo) * 1e-3, 1e-12)
        lo, hi = lo - pad, hi + pad
    norm = matplotlib.colors.Normalize(lo, hi)
    colormap = matplotlib.colormaps[cmap]
    faces = colormap(norm(colour))
    # Mild Lambert shading by a light from the viewer's side, so that the
    # shape reads even where the colour is uniform (at most 25 % darker).
    normals = np.cross(polygons[:, 2] - polygons[:, 0], polygons[:, 3] - polygons[:, 1])
    normals /= np.maximum(np.linalg.norm(normals, axis=1, keepdims=True), 1e-300)
    elev, azim = np.radians(view[0]), np.radians(view[1])
    light = np.array([np.cos(elev) * np.cos(azim), np.cos(elev) * np.sin(azim), np.sin(elev)])
    light = light + np.array([0.0, 0.0, 0.6])
    light /= np.linalg.norm(light)
    faces[:, :3] *= (0.75 + 0.25 * np.abs(normals @ light))[:, None]
    edge_width = 0.25 if len(polygons) <= 4000 else 0.0
    fig = plt.figure(figsize=(8.0, 6.4), dpi=110)
    try:
        ax = fig.add_subplot(projection="3d")
        collection = Poly3DCollection(polygons, facecolors=faces, edgecolors=(0.1, 0.1, 0.1, 0.35),
                                      linewidths=edge_width)
        ax.add_collection3d(collection)
        pts = polygons.reshape(-1, 3)
        pmin, pmax = pts.min(axis=0), pts.max(axis=0)
        span = np.maximum(pmax - pmin, 1e-3 * (pmax - pmin).max())
        centre = 0.5 * (pmin + pmax)
        ax.set_xlim(centre[0] - span[0] / 2, centre[0] + span[0] / 2)
        ax.set_ylim(centre[1] - span[1] / 2, centre[1] + span[1] / 2)
        ax.set_zlim(centre[2] - span[2] / 2, centre[2] + span[2] / 2)
        ax.set_box_aspect(tuple(span))  # equal aspect: one unit is as long on every axis
        ax.view_init(elev=view[0], azim=view[1])
        ax.set_xlabel("x")
        ax.set_ylabel("y")
        ax.set_zlabel("z")
        mappable = matplotlib.cm.ScalarMappable(norm=norm, cmap=colormap)
        mappable.set_array(colour)
        fig.colorbar(mappable, ax=ax, shrink=0.6, pad=0.1, label=label)
        if title:
            ax.set_title(title, fontsize=10)
        # mplot3d leaves the z label out of the tight box: keep it in explicitly.
        fig.savefig(png_path, bbox_inches="tight", pad_inches=0.2,
                    bbox_extra_artists=[ax.xaxis.label, ax.yaxis.label, ax.zaxis.label])
    finally:
        plt.close(fig)
