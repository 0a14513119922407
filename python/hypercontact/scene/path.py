"""The load path of a scene: every value a run drives — each fixed bc
component, each load, each rigid obstacle's translation and rotation, each
contact's μ and whether it acts — as a function of (phase k, its parameter s in [0, 1]). Pure:
no mesh, no solver (tested in tests/unit; the model applies it, the rules check it).

Without [[phase]] the scene is one phase in which every motion and load
goes linearly from 0 to the scene's value (u = λ × motion) and μ is the
scene's. With [[phase]] (:mod:`hypercontact.scene.phases`) everything
starts at zero, μ at the scene's value, and each phase moves what it names
from where the previous phase left it, along its points [s, value]."""
import math
from dataclasses import dataclass, field

import numpy as np

from .errors import Invalid

AXIS = {"x": 0, "y": 1, "z": 2}
#: the loads a phase can name, with the size of their value
LOADS = {"pressure": 1, "traction": 3, "body_force": 3}


class Channel:
    """One value along the path: ``starts[k]`` where phase k starts, ``points[k]``
    its points [(s, value)] (None: it holds its value through phase k)."""

    def __init__(self, initial, points_per_phase):
        self.points = points_per_phase
        self.starts = []
        value = initial
        for points in points_per_phase:
            self.starts.append(value)
            if points:
                value = points[-1][1]
        self.end = value

    def at(self, k, s):
        """The value in phase k at parameter s: linear between the points, the
        phase's start value at s = 0, the last point's value after it. Beyond
        s = 1 (continuation's λ may go there) the segment that ends at s = 1 is
        extended, and before s = 0 the first one."""
        start, points = self.starts[k], self.points[k]
        if not points:
            return start
        s0, v0 = 0.0, start
        for s1, v1 in points:
            if s <= s1 or (s1 == 1.0 and s > 1.0):
                if s1 == s0:
                    return v1
                return _add(v0, _scale((s - s0) / (s1 - s0), _sub(v1, v0)))
            s0, v0 = s1, v1
        return v0

    def changes_in(self, k):
        return bool(self.points[k])

    def moves(self):
        """Whether the value is ever other than where it starts."""
        return any(points for points in self.points)


def _sub(a, b):
    return [x - y for x, y in zip(a, b)] if isinstance(a, list) else a - b


def _add(a, b):
    return [x + y for x, y in zip(a, b)] if isinstance(a, list) else a + b


def _scale(t, a):
    return [t * x for x in a] if isinstance(a, list) else t * a


@dataclass
class PhaseSpec:
    """A phase as the run uses it: name, length, start τ, and its [steps] and [solver] (the scene's, with the phase's keys)."""

    name: str
    length: float
    start: float
    steps: dict
    solver: dict
    given: dict = field(default_factory=dict)  # the phase's table as written (empty for the implicit phase)


def rotation_matrix(axis, angle):
    """Rodrigues: the rotation by ``angle`` (rad, right-handed) about the unit ``axis``."""
    a = np.asarray(axis, dtype=float)
    a = a / np.linalg.norm(a)
    K = np.array([[0.0, -a[2], a[1]], [a[2], 0.0, -a[0]], [-a[1], a[0], 0.0]])
    return np.eye(3) + math.sin(angle) * K + (1.0 - math.cos(angle)) * (K @ K)


class LoadPath:
    """The channels of a scene (a plain dict, :func:`hypercontact.scene.load`)."""

    def __init__(self, scene):
        self.scene = scene
        given = scene.get("phase", [])
        self.implicit = not given
        t, self.phases = 0.0, []
        for k, ph in enumerate(given or [{}]):
            length = float(ph.get("length", 1.0))
            self.phases.append(PhaseSpec(ph.get("name") or (f"phase {k + 1}" if given else "load"), length, t,
                                         {**scene["steps"], **ph.get("steps", {})},
                                         {**scene["solver"], **ph.get("solver", {})}, ph))
            t += length
        self.channels = {}
        self.ended = {}  # phase → the parameter s it ended at, where not 1 (continuation phases)
        self._bcs(scene, given)
        self._loads(scene, given)
        self._contacts(scene, given)

    # --- building -------------------------------------------------------------------
    def _named(self, section, name):
        return next(i for i, e in enumerate(self.scene[section]) if e.get("name") == name)

    def _per_phase(self, given, section, name, key=None):
        """Each phase's points of entry ``name`` in its ``section`` table (key: of a contact's table)."""
        out = []
        for ph in given:
            entry = ph.get(section, {}).get(name)
            if entry is not None and key is not None:
                entry = entry.get(key)
            out.append(entry)
        return out

    def _bcs(self, scene, given):
        for i, bc in enumerate(scene["bc"]):
            for a in bc["fix"]:
                if self.implicit:
                    points = [[[1.0, float(bc["motion"][AXIS[a]])]]]
                elif bc.get("name"):
                    points = [[[s, v[AXIS[a]]] for s, v in p] if p else None
                              for p in self._per_phase(given, "bc", bc["name"])]
                else:
                    points = [None] * len(given)
                self.channels[("bc", i, a)] = Channel(0.0, points)

    def _loads(self, scene, given):
        for section, size in LOADS.items():
            for i, load in enumerate(scene[section]):
                zero = 0.0 if size == 1 else [0.0, 0.0, 0.0]
                if self.implicit:
                    points = [[[1.0, load["value"]]]]
                elif load.get("name"):
                    points = self._per_phase(given, section, load["name"])
                else:
                    points = [None] * len(given)
                self.channels[(section, i)] = Channel(zero, points)

    def _contacts(self, scene, given):
        for j, c in enumerate(scene["contact"]):
            n = len(given) or 1
            if c["obstacle"] != "surface":
                motion = ([[[1.0, [float(v) for v in c["motion"]]]]] if self.implicit else
                          self._per_phase(given, "contact", c["name"], "motion"))
                self.channels[("motion", j)] = Channel([0.0, 0.0, 0.0], motion)
                rotation = [None] if self.implicit else self._per_phase(given, "contact", c["name"], "rotation")
                self.channels[("rotation", j)] = Channel(0.0, rotation)
            mu = [None] * n if self.implicit else self._per_phase(given, "contact", c["name"], "mu")
            self.channels[("mu", j)] = Channel(float(c["mu"]), mu)
            # the pair's share of its penalty: 1 on, 0 off. Switched off, it is 0 from the phase's
            # first step (a point at s = 0 holds through the phase); switched on, it ramps in, 0 → 1
            # over the phase, so that an overclosure is resolved in steps the controller can cut
            active = [None] * n if self.implicit else self._per_phase(given, "contact", c["name"], "active")
            value, points = (1.0 if c.get("active", True) else 0.0), []
            for a in active:
                if a is None or float(a) == value:
                    points.append(None)
                else:
                    value = float(a)
                    points.append([[1.0, 1.0]] if a else [[0.0, 0.0]])
            self.channels[("active", j)] = Channel(1.0 if c.get("active", True) else 0.0, points)

    # --- reading --------------------------------------------------------------------
    def values(self, k, s):
        """Every channel's value in phase k at its parameter s."""
        return {key: ch.at(k, s) for key, ch in self.channels.items()}

    def time(self, k, s):
        """The accumulated load parameter τ: phase k spans [start, start + length]."""
        ph = self.phases[k]
        return ph.start + s * ph.length

    def progress(self, k, s):
        """The fraction of the whole path done at parameter s of phase k."""
        end = self.phases[-1].start + self.phases[-1].length
        return self.time(k, s) / end

    def max_mu(self, j):
        """The largest μ contact j has anywhere on the path."""
        ch = self.channels[("mu", j)]
        return max([ch.starts[0]] + [v for points in ch.points if points for _, v in points])

    def rates(self, k):
        """∂value/∂s of every load in phase k ({(section, i): rate}): a
        continuation phase drives its loads linearly, from where the phase
        starts to its end value."""
        out = {}
        for key, ch in self.channels.items():
            if key[0] in LOADS:
                points = ch.points[k]
                out[key] = _sub(points[-1][1], ch.starts[k]) if points else _scale(0.0, ch.starts[k])
        return out

    def end_phase_at(self, k, s):
        """Phase k ended at parameter s, not 1 (a continuation phase stops when
        its probe reaches stop_value): the phases after it start from the
        values there, and their τ from start_k + s × length_k."""
        if s == 1.0:
            return
        self.ended[k] = s
        for ch in self.channels.values():
            value = ch.at(k, s)
            for j in range(k + 1, len(ch.points)):
                ch.starts[j] = value
                if ch.points[j]:
                    value = ch.points[j][-1][1]
            ch.end = value
        t = self.time(k, s)
        for ph in self.phases[k + 1:]:
            ph.start = t
            t += ph.length

    def active(self, k, j):
        """Whether contact j acts at the end of phase k (switched on in it: ramped in by its end)."""
        return self.channels[("active", j)].at(k, 1.0) > 0.0

    def switch(self, k, j):
        """'on', 'off' or None: what phase k does to contact j."""
        before = self.channels[("active", j)].starts[k] > 0.0
        return None if before == self.active(k, j) else ("on" if self.active(k, j) else "off")

    def rotates(self, j):
        ch = self.channels.get(("rotation", j))
        return ch is not None and ch.moves()

    def moving_bcs(self):
        """Number of bc components that move somewhere on the path."""
        return sum(ch.moves() and any(v != 0.0 for points in ch.points if points for _, v in points)
                   for key, ch in self.channels.items() if key[0] == "bc")

    def append_phase(self, name, starts, ends):
        """A phase added after the last (the Python API, :func:`hypercontact.phases.run_phase`),
        from ``starts`` (every channel's value where the run is now) to ``ends``
        {channel key: its value at the phase end}; the others hold."""
        start = self.phases[-1].start + self.phases[-1].length
        self.phases.append(PhaseSpec(name, 1.0, start, dict(self.scene["steps"]), dict(self.scene["solver"])))
        for key, ch in self.channels.items():
            ch.points.append([[1.0, ends[key]]] if key in ends else None)
            ch.starts.append(starts[key])
            ch.end = ends.get(key, starts[key])
        return len(self.phases) - 1


def check_no_jumps(path):
    """Invalid naming the first curve whose point at s = 0 is not where its
    value is when its phase starts (a bc or an obstacle would jump)."""
    names = {"bc": "bc", "pressure": "pressure", "traction": "traction", "body_force": "body_force",
             "motion": "contact", "rotation": "contact", "mu": "contact"}
    for key, ch in path.channels.items():
        if key[0] == "active":  # a switch, not a curve: it acts from the phase's start
            continue
        for k, points in enumerate(ch.points):
            if not points or points[0][0] != 0.0:
                continue
            start, first = ch.starts[k], points[0][1]
            if not np.allclose(np.atleast_1d(first), np.atleast_1d(start), rtol=0.0, atol=1e-12 *
                               max(1.0, float(np.max(np.abs(np.atleast_1d(start)))))):
                section = names[key[0]]
                entry = path.scene[section if section != "contact" else "contact"][key[1]]
                loc = ("phase", k, section, entry["name"]) + ((key[0],) if section == "contact" else ())
                raise Invalid(f"the curve starts at {first} at s = 0, but the value is {start} where phase "
                              f"{k + 1} starts (the end of the previous phase): it would jump; start the curve "
                              "there or leave out the point at s = 0", loc + (0,))
