"""``curves.png`` and ``deformed.png``, drawn at the end of a run that
converged at least one step (completed or not; :mod:`hypercontact.pictures`):
the contact forces (or pressures) against the first contact's displacement
(or the first probe's), and the deformed boundary coloured by |u|. A picture
that cannot be drawn never stops a run: summary.json says why (``"pictures"``)."""
import numpy as np
from mpi4py import MPI

from .. import _dolfinx as dfx


def curve_columns(w):
    """(x, ys) drawn in curves.png: under continuation, the path it
    follows: the pressures (else the load factor) against the stop probe's
    controlled component; else the contact forces (each contact's largest
    component) against the first contact's displacement (with phases:
    against the accumulated parameter τ, ``time``); without contacts, the
    pressures (else the load factor) against the first probe's largest
    displacement component."""
    def largest(columns):
        return max(columns, key=lambda c: max(abs(s[c]) for s in w.steps))

    st = w.scene["steps"]
    continuation = st.get("control", "load") != "load" and st.get("stop_probe") in w.probes
    if w.contacts and not continuation:
        x = f"{w.contacts[0].name}_displacement" if w.path.implicit else "time"
        return x, [largest([f"{c.name}_f{a}" for a in "xyz"]) for c in w.contacts]
    if continuation:
        x = f"{st['stop_probe']}_u{st['stop_component']}"
    elif w.probes:
        x = largest([f"{next(iter(w.probes))}_u{a}" for a in "xyz"])
    else:
        x = "load_factor"
    ys = list(w.pressures) or (["load_factor"] if x != "load_factor" else ["newton_iterations"])
    return x, ys


def draw_pictures(w):
    """curves.png (rank 0) and deformed.png (collective) of the last
    converged step. Never raises: returns what was drawn, or why not.
    Every collective call is reached on every rank, whatever fails."""
    if not w.steps or w._u_last is None:
        return {"skipped": "no converged step"}
    done, error = {}, None
    try:
        from .. import pictures
    except Exception as err:  # e.g. matplotlib missing
        error = f"failed: {type(err).__name__}: {err}"
    errors = [e for e in w.comm.allgather(error) if e]
    if errors:
        return {"curves.png": errors[0], "deformed.png": errors[0]}
    title = w.scene.get("title") or w.out.name
    if w.rank0:
        try:
            x, ys = curve_columns(w)
            pictures.load_curves(w.out / "curves.csv", w.out / "curves.png", x, ys, title=title)
            done["curves.png"] = f"{', '.join(ys)} against {x}"
        except Exception as err:
            done["curves.png"] = f"failed: {type(err).__name__}: {err}"
    try:
        u = dfx.fem.Function(w.u.function_space, name="displacement")
        u.x.array[:] = w._u_last
    except Exception as err:
        u, error = None, f"failed: {type(err).__name__}: {err}"
    errors = [e for e in w.comm.allgather(error) if e]
    if errors:
        done["deformed.png"] = errors[0]
        return done
    scale = picture_scale(w.comm, u)
    last = w.steps[-1]
    magnified = f", displacements × {scale:g}" if scale != 1 else ""
    # With contacts, look from the low-x, low-y side: the symmetry cuts of a
    # quarter model and what an obstacle presses into them show. Without,
    # from the high side: the outside of a shell octant.
    view = (28.0, -130.0) if w.contacts else (28.0, 50.0)
    try:  # collective, and raises on every rank or on none
        pictures.deformed_shape(
            w.u.function_space.mesh, u, None, w.out / "deformed.png", scale=scale, view=view,
            title=f"{title}\nstep {last['step']}, load factor {last['load_factor']:.4g}{magnified}")
        done["deformed.png"] = f"|u| on the deformed boundary at step {last['step']}{magnified}"
    except Exception as err:
        done["deformed.png"] = f"failed: {type(err).__name__}: {err}"
    return done


def picture_scale(comm, u):
    """1, or a round magnification when the largest displacement is below
    2 % of the body's size (so that the deformation shows). Collective."""
    x = u.function_space.mesh.geometry.x
    extent = np.full(7, -np.inf)  # −min x, max x, max |u|
    if len(x):
        extent[:3], extent[3:6] = -x.min(axis=0), x.max(axis=0)
    U = u.x.array.reshape(-1, 3)
    if len(U):
        extent[6] = np.linalg.norm(U, axis=1).max()
    comm.Allreduce(MPI.IN_PLACE, extent, op=MPI.MAX)
    size, umax = float(np.linalg.norm(extent[3:6] + extent[:3])), float(extent[6])
    if not np.isfinite(umax) or umax <= 0.0 or umax >= 0.02 * size:
        return 1.0
    target = 0.1 * size / umax
    return float(max(m * 10.0 ** e for e in range(0, 9) for m in (1, 2, 5) if m * 10.0 ** e <= target))
