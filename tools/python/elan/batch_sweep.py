# SPDX-License-Identifier: MIT
"""Sweep files for ``elan.batch``: one scene with parameters varied, expanded into cases.

A sweep is a JSON (or YAML) object; docs/batch.md describes it. This module reads and checks it
(every error names the file and the field, as the scene loader's do) and turns it into a list of
cases, each a plain dict holding the scene JSON text it simulates, so that a case is a pure
function of the sweep: the same sweep gives the same cases, in the same order, on any machine.
"""

from __future__ import annotations

import copy
import itertools
import json
import math
import os
from typing import Any, Iterable

# Parameters a sweep may vary, besides JSON pointers ("/bodies/3/position").
PARAMETERS = (
    "scene",
    "steps",
    "gravity",
    "friction",
    "restitution",
    "seed",
    "timestep",
    "substeps",
    "iterations",
    "allow_sleep",
)
# Keys of the sweep object that are not parameters.
SWEEP_KEYS = ("grid", "cases", "piles", "trajectory", "broadphase")
PILE_KEYS = ("count", "spacing", "origin", "body", "jitter", "random_orientation")
TRAJECTORY_KEYS = ("format", "every")
BROADPHASES = ("sap", "all-pairs", "tree")
DEFAULT_STEPS = 600  # as `elan run`

# The supported ranges of docs/scene-format.md, checked here so that a bad sweep fails before any
# task runs, with the sweep's field named.
MAX_GRAVITY = 1e5  # m/s^2
MAX_FRICTION = 100.0
MAX_RESTITUTION = 1.0
MIN_TIMESTEP, MAX_TIMESTEP = 1e-6, 1.0  # s
MAX_SOLVER_COUNT = 10000  # substeps, iterations
MAX_STEPS = 10**9
MAX_PILE_BODIES = 10**6
MAX_POSITION = 1e5  # m


class SweepError(ValueError):
    """A bad sweep: ``str()`` is one line naming the file and the field; ``.field`` is the field."""

    def __init__(self, path: str, field: str, message: str):
        self.path = path
        self.field = field
        self.message = message
        where = f"{path}: " if path else ""
        super().__init__(f"{where}{field}: {message}" if field else f"{where}{message}")


def _is_number(v: Any) -> bool:
    # bool is an int in Python; a sweep saying `"friction": true` is a mistake.
    return isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v)


def _is_int(v: Any) -> bool:
    return isinstance(v, int) and not isinstance(v, bool)


def _show(v: Any) -> str:
    text = json.dumps(v) if not isinstance(v, float) else repr(v)
    return text if len(text) <= 60 else text[:57] + "..."


def _vec3(path: str, field: str, v: Any, limit: float | None = None) -> list:
    if not (isinstance(v, list) and len(v) == 3 and all(_is_number(x) for x in v)):
        raise SweepError(path, field, f"must be [x, y, z], three finite numbers, got {_show(v)}")
    if limit is not None and any(abs(x) > limit for x in v):
        raise SweepError(path, field, f"each component must be within +-{limit:g}, got {_show(v)}")
    return list(v)


def check_parameter(path: str, field: str, name: str, v: Any) -> Any:
    """Checks one value of parameter ``name``; returns it normalised. Raises SweepError."""
    if name.startswith("/"):
        return v  # a JSON pointer: any JSON value, checked by the scene loader
    if name == "scene":
        if isinstance(v, str) and v:
            return v
        if isinstance(v, dict):
            return v
        raise SweepError(path, field, f"must be a scene file path or a scene object, got {_show(v)}")
    if name == "steps":
        if not (_is_int(v) and 0 <= v <= MAX_STEPS):
            raise SweepError(path, field, f"must be an integer from 0 to {MAX_STEPS}, got {_show(v)}")
        return v
    if name == "gravity":
        if _is_number(v):  # a number g is [0, -g, 0]: the default frame has Y up
            if abs(v) > MAX_GRAVITY:
                raise SweepError(path, field, f"must be within +-{MAX_GRAVITY:g} m/s^2, got {_show(v)}")
            return [0.0, -float(v), 0.0] if v != 0 else [0.0, 0.0, 0.0]
        return _vec3(path, field, v, MAX_GRAVITY)
    if name == "friction":
        if not (_is_number(v) and 0 <= v <= MAX_FRICTION):
            raise SweepError(path, field, f"must be a number from 0 to {MAX_FRICTION:g}, got {_show(v)}")
        return v
    if name == "restitution":
        if not (_is_number(v) and 0 <= v <= MAX_RESTITUTION):
            raise SweepError(
                path, field, f"must be a number from 0 to {MAX_RESTITUTION:g}, got {_show(v)}"
            )
        return v
    if name == "seed":
        if not (_is_int(v) and 0 <= v < 2**64):
            raise SweepError(path, field, f"must be an integer from 0 to 2^64-1, got {_show(v)}")
        return v
    if name == "timestep":
        if not (_is_number(v) and MIN_TIMESTEP <= v <= MAX_TIMESTEP):
            raise SweepError(
                path, field, f"must be a number from {MIN_TIMESTEP:g} to {MAX_TIMESTEP:g} s, got {_show(v)}"
            )
        return v
    if name in ("substeps", "iterations"):
        if not (_is_int(v) and 1 <= v <= MAX_SOLVER_COUNT):
            raise SweepError(path, field, f"must be an integer from 1 to {MAX_SOLVER_COUNT}, got {_show(v)}")
        return v
    if name == "allow_sleep":
        if not isinstance(v, bool):
            raise SweepError(path, field, f"must be true or false, got {_show(v)}")
        return v
    known = ", ".join(PARAMETERS + SWEEP_KEYS)
    raise SweepError(path, field, f"unknown parameter (known: {known}, or a JSON pointer '/...')")


def _check_pile(path: str, field: str, pile: Any) -> dict:
    if not isinstance(pile, dict):
        raise SweepError(path, field, f"must be an object, got {_show(pile)}")
    for key in pile:
        if key not in PILE_KEYS:
            raise SweepError(path, f"{field}.{key}", f"unknown key (known: {', '.join(PILE_KEYS)})")
    for key in ("count", "spacing", "body"):
        if key not in pile:
            raise SweepError(path, f"{field}.{key}", "missing")
    count = pile["count"]
    if not (isinstance(count, list) and len(count) == 3 and all(_is_int(c) and c >= 1 for c in count)):
        raise SweepError(path, f"{field}.count", f"must be [nx, ny, nz], integers >= 1, got {_show(count)}")
    if count[0] * count[1] * count[2] > MAX_PILE_BODIES:
        raise SweepError(path, f"{field}.count", f"at most {MAX_PILE_BODIES} bodies a pile")
    spacing = _vec3(path, f"{field}.spacing", pile["spacing"], MAX_POSITION)
    if any(s <= 0 for s in spacing):
        raise SweepError(path, f"{field}.spacing", f"must be positive, got {_show(spacing)}")
    origin = _vec3(path, f"{field}.origin", pile.get("origin", [0, 0, 0]), MAX_POSITION)
    jitter = pile.get("jitter", 0)
    if not (_is_number(jitter) and jitter >= 0):
        raise SweepError(path, f"{field}.jitter", f"must be a number >= 0 (m), got {_show(jitter)}")
    random_orientation = pile.get("random_orientation", False)
    if not isinstance(random_orientation, bool):
        raise SweepError(path, f"{field}.random_orientation", f"must be true or false, got {_show(random_orientation)}")
    body = pile["body"]
    if not isinstance(body, dict):
        raise SweepError(path, f"{field}.body", f"must be a body object, got {_show(body)}")
    for key in ("name", "position"):
        if key in body:
            raise SweepError(path, f"{field}.body.{key}", "a pile places its bodies and cannot name them")
    if random_orientation and "orientation" in body:
        raise SweepError(path, f"{field}.body.orientation", "given with random_orientation")
    return {
        "count": list(count),
        "spacing": spacing,
        "origin": origin,
        "jitter": jitter,
        "random_orientation": random_orientation,
        "body": body,
    }


# --- the piles' random numbers ------------------------------------------------------------------
# determinism: SplitMix64 (Steele, Lea and Flood, "Fast splittable pseudorandom number generators",
# OOPSLA 2014) in integer arithmetic, so a seed gives the same bodies on every machine and with
# every Python and NumPy version; NumPy's generators promise no such stability across versions.
_MASK = (1 << 64) - 1


class SplitMix64:
    def __init__(self, seed: int):
        self.state = seed & _MASK

    def next_u64(self) -> int:
        self.state = (self.state + 0x9E3779B97F4A7C15) & _MASK
        z = self.state
        z = ((z ^ (z >> 30)) * 0xBF58476D1CE4E5B9) & _MASK
        z = ((z ^ (z >> 27)) * 0x94D049BB133111EB) & _MASK
        return z ^ (z >> 31)

    def uniform(self) -> float:
        """A double in [0, 1): the top 53 bits, exactly representable."""
        return (self.next_u64() >> 11) * (1.0 / (1 << 53))


def pile_bodies(pile: dict, seed: int, pile_index: int) -> list:
    """The bodies of one pile: a grid as the scene's ``grid`` generator places it (x fastest, then
    y, then z), each position moved by up to ``jitter`` along each axis, and with
    ``random_orientation`` a uniformly distributed orientation (Shoemake, "Uniform random
    rotations", Graphics Gems III, 1992)."""
    # Each pile draws from its own stream, so adding a pile leaves the earlier ones unchanged.
    rng = SplitMix64(seed ^ ((pile_index + 1) * 0xD1B54A32D192ED03 & _MASK))
    nx, ny, nz = pile["count"]
    sx, sy, sz = pile["spacing"]
    ox, oy, oz = pile["origin"]
    jitter = pile["jitter"]
    out = []
    for k in range(nz):
        for j in range(ny):
            for i in range(nx):
                body = copy.deepcopy(pile["body"])
                base = (ox + i * sx, oy + j * sy, oz + k * sz)
                body["position"] = [b + jitter * (2.0 * rng.uniform() - 1.0) for b in base]
                if pile["random_orientation"]:
                    u1, u2, u3 = rng.uniform(), rng.uniform(), rng.uniform()
                    a, b = math.sqrt(1.0 - u1), math.sqrt(u1)
                    t2, t3 = 2.0 * math.pi * u2, 2.0 * math.pi * u3
                    # [w, x, y, z]; a unit quaternion up to rounding, normalised on load.
                    body["orientation"] = [b * math.cos(t3), a * math.sin(t2), a * math.cos(t2), b * math.sin(t3)]
                out.append(body)
    return out


# --- applying parameters to a scene -------------------------------------------------------------


def _material_targets(scene: dict) -> Iterable[dict]:
    """The objects whose ``friction`` and ``restitution`` are the scene's materials: every body,
    a ``grid``'s body, a ``chain``'s link and a ``terrain``. Pyramids, ragdolls and joint grids
    have no material keys and keep the defaults."""
    for body in scene.get("bodies", []) or []:
        if isinstance(body, dict):
            yield body
    for gen in scene.get("generators", []) or []:
        if not isinstance(gen, dict):
            continue
        kind = gen.get("type")
        if kind == "grid" and isinstance(gen.get("body"), dict):
            yield gen["body"]
        elif kind == "chain" and isinstance(gen.get("link"), dict):
            yield gen["link"]
        elif kind == "terrain":
            yield gen


def _set_pointer(path: str, field: str, scene: dict, pointer: str, value: Any) -> None:
    """RFC 6901: sets the value at ``pointer``; the parent must exist; the last token may name a
    new key of an object or an existing index of an array."""
    tokens = [t.replace("~1", "/").replace("~0", "~") for t in pointer[1:].split("/")]
    node: Any = scene
    for depth, token in enumerate(tokens):
        last = depth == len(tokens) - 1
        where = "/" + "/".join(tokens[: depth + 1])
        if isinstance(node, dict):
            if last:
                node[token] = copy.deepcopy(value)
                return
            if token not in node:
                raise SweepError(path, field, f"the scene has no {where}")
            node = node[token]
        elif isinstance(node, list):
            if not (token.isdigit() and int(token) < len(node)):
                raise SweepError(path, field, f"the scene has no {where}")
            if last:
                node[int(token)] = copy.deepcopy(value)
                return
            node = node[int(token)]
        else:
            raise SweepError(path, field, f"the scene has no {where}")


def apply_parameters(scene: dict, params: dict, piles: list, fields: dict, path: str = "") -> dict:
    """A copy of ``scene`` with the parameters set. ``fields`` maps a parameter to the sweep field
    that gave it (for messages)."""
    scene = copy.deepcopy(scene)
    if piles:
        bodies = scene.setdefault("bodies", [])
        if not isinstance(bodies, list):
            raise SweepError(path, "piles", "the scene's 'bodies' is not a list")
        first_generated = len(bodies)
        seed = params.get("seed", 0)
        added = []
        for p, pile in enumerate(piles):
            added.extend(pile_bodies(pile, seed, p))
        bodies.extend(added)
        # The pile's bodies go after the scene's own, before the generated ones, so joints that
        # name a generated body by index move up by the pile's size.
        for joint in scene.get("joints", []) or []:
            if isinstance(joint, dict) and isinstance(joint.get("bodies"), list):
                joint["bodies"] = [
                    b + len(added) if _is_int(b) and b >= first_generated else b for b in joint["bodies"]
                ]
    for key in ("gravity", "timestep", "substeps", "iterations", "allow_sleep"):
        if key in params:
            scene[key] = params[key]
    for key in ("friction", "restitution"):
        if key in params:
            for target in _material_targets(scene):
                target[key] = params[key]
    for key, value in params.items():
        if key.startswith("/"):
            _set_pointer(path, fields.get(key, key), scene, key, value)
    return scene


# --- reading a sweep ----------------------------------------------------------------------------


def _read_document(path: str) -> Any:
    try:
        with open(path, "rb") as f:
            data = f.read()
    except OSError as e:
        raise SweepError(path, "", f"cannot read: {e.strerror or e}") from None
    if path.endswith((".yaml", ".yml")):
        try:
            import yaml
        except ImportError:
            raise SweepError(path, "", "YAML sweeps need PyYAML (Debian: python3-yaml)") from None
        try:
            return yaml.safe_load(data)
        except yaml.YAMLError as e:
            mark = getattr(e, "problem_mark", None)
            where = f" at line {mark.line + 1}, column {mark.column + 1}" if mark else ""
            raise SweepError(path, "", f"malformed YAML{where}: {getattr(e, 'problem', e)}") from None
    try:
        return json.loads(data, object_pairs_hook=_no_duplicates)
    except _DuplicateKey as e:
        raise SweepError(path, str(e), "duplicate key") from None
    except (json.JSONDecodeError, UnicodeDecodeError) as e:
        raise SweepError(path, "", f"malformed JSON: {e}") from None


class _DuplicateKey(ValueError):
    pass


def _no_duplicates(pairs):
    out = {}
    for k, v in pairs:
        if k in out:
            raise _DuplicateKey(k)
        out[k] = v
    return out


class Sweep:
    """A checked sweep: ``cases()`` lists what to simulate, in sweep order."""

    def __init__(self, doc: Any, path: str = "", base_dir: str | None = None):
        self.path = path
        self.base_dir = base_dir if base_dir is not None else (os.path.dirname(os.path.abspath(path)) if path else os.getcwd())
        if not isinstance(doc, dict):
            raise SweepError(path, "", f"a sweep must be an object, got {_show(doc)}")
        self.defaults: dict = {}
        self.fields: dict = {}
        for key, value in doc.items():
            if key in SWEEP_KEYS:
                continue
            self.defaults[key] = check_parameter(path, key, key, value)
            self.fields[key] = key
        self.grid: list[tuple[str, list]] = []
        grid = doc.get("grid", {})
        if not isinstance(grid, dict):
            raise SweepError(path, "grid", f"must be an object of parameter: [values], got {_show(grid)}")
        for key, values in grid.items():
            field = f"grid.{key}"
            if not isinstance(values, list) or not values:
                raise SweepError(path, field, f"must be a non-empty list of values, got {_show(values)}")
            self.grid.append((key, [check_parameter(path, f"{field}[{i}]", key, v) for i, v in enumerate(values)]))
        self.cases_list: list[dict] = []
        cases = doc.get("cases", [])
        if not isinstance(cases, list):
            raise SweepError(path, "cases", f"must be a list of objects, got {_show(cases)}")
        for i, case in enumerate(cases):
            if not isinstance(case, dict):
                raise SweepError(path, f"cases[{i}]", f"must be an object of parameters, got {_show(case)}")
            checked = {}
            for key, value in case.items():
                field = f"cases[{i}].{key}"
                if key in SWEEP_KEYS:
                    raise SweepError(path, field, "not a parameter (it belongs at the top of the sweep)")
                if key in grid:
                    raise SweepError(path, field, "also varied by grid")
                checked[key] = check_parameter(path, field, key, value)
            self.cases_list.append(checked)
        piles = doc.get("piles", [])
        if not isinstance(piles, list):
            raise SweepError(path, "piles", f"must be a list of piles, got {_show(piles)}")
        self.piles = [_check_pile(path, f"piles[{i}]", p) for i, p in enumerate(piles)]
        if not self.piles:
            for field, name in self._parameter_fields():
                if name == "seed":
                    raise SweepError(path, field, "a seed seeds the piles, and the sweep has none ('piles')")
        self.trajectory = self._check_trajectory(doc.get("trajectory"))
        self.broadphase = doc.get("broadphase", "sap")
        if self.broadphase not in BROADPHASES:
            raise SweepError(path, "broadphase", f"must be one of {', '.join(BROADPHASES)}, got {_show(self.broadphase)}")
        has_scene = "scene" in self.defaults or any(k == "scene" for k, _ in self.grid)
        if not has_scene:
            for i, case in enumerate(self.cases_list):
                if "scene" not in case:
                    field = f"cases[{i}].scene" if self.cases_list else "scene"
                    raise SweepError(path, field, "missing: no scene to simulate")
            if not self.cases_list:
                raise SweepError(path, "scene", "missing: no scene to simulate")
        self._scenes: dict = {}

    def _parameter_fields(self):
        for key in self.defaults:
            yield key, key
        for key, _ in self.grid:
            yield f"grid.{key}", key
        for i, case in enumerate(self.cases_list):
            for key in case:
                yield f"cases[{i}].{key}", key

    def _check_trajectory(self, t: Any) -> dict | None:
        if t is None or t is False:
            return None
        if t is True:
            t = {}
        if not isinstance(t, dict):
            raise SweepError(self.path, "trajectory", f"must be an object {{format, every}}, got {_show(t)}")
        for key in t:
            if key not in TRAJECTORY_KEYS:
                raise SweepError(self.path, f"trajectory.{key}", f"unknown key (known: {', '.join(TRAJECTORY_KEYS)})")
        fmt = t.get("format", "csv")
        if fmt not in ("csv", "npz"):
            raise SweepError(self.path, "trajectory.format", f"must be \"csv\" or \"npz\", got {_show(fmt)}")
        every = t.get("every", 1)
        if not (_is_int(every) and every >= 1):
            raise SweepError(self.path, "trajectory.every", f"must be an integer >= 1, got {_show(every)}")
        return {"format": fmt, "every": every}

    def points(self) -> list[tuple[dict, dict]]:
        """The parameter sets in sweep order, each with the sweep field of each value: every case
        (in the order listed) times every grid point (the grid's first key slowest, its last
        fastest, as nested loops in the order written)."""
        cases = self.cases_list or [{}]
        out = []
        for c, case in enumerate(cases):
            keys = [k for k, _ in self.grid]
            for combo in itertools.product(*[list(enumerate(v)) for _, v in self.grid]):
                params = dict(self.defaults)
                fields = dict(self.fields)
                for key, (i, value) in zip(keys, combo):
                    params[key] = value
                    fields[key] = f"grid.{key}[{i}]"
                for key, value in case.items():
                    params[key] = value
                    fields[key] = f"cases[{c}].{key}"
                out.append((params, fields))
        return out

    def _scene(self, ref: Any, field: str) -> tuple[dict, str, str]:
        """(scene object, label, base directory) for a scene reference."""
        if isinstance(ref, dict):
            return ref, "inline", self.base_dir
        full = ref if os.path.isabs(ref) else os.path.join(self.base_dir, ref)
        if full not in self._scenes:
            try:
                with open(full, "rb") as f:
                    doc = json.loads(f.read())
            except OSError as e:
                raise SweepError(self.path, field, f"{ref}: cannot read: {e.strerror or e}") from None
            except (json.JSONDecodeError, UnicodeDecodeError) as e:
                raise SweepError(self.path, field, f"{ref}: malformed JSON: {e}") from None
            if not isinstance(doc, dict):
                raise SweepError(self.path, field, f"{ref}: a scene must be a JSON object")
            self._scenes[full] = doc
        return self._scenes[full], ref, os.path.dirname(os.path.abspath(full))

    def cases(self) -> list[dict]:
        """Every case, in sweep order: a dict of ``index``, ``params`` (the parameters as the
        results show them), ``scene_text`` (the modified scene), ``scene_name``, ``base_dir``,
        ``steps``, ``broadphase`` and ``trajectory``."""
        out = []
        for index, (params, fields) in enumerate(self.points()):
            scene, label, base_dir = self._scene(params["scene"], fields["scene"])
            modified = apply_parameters(scene, params, self.piles, fields, self.path)
            shown = {k: v for k, v in params.items() if k != "scene"}
            shown = {"scene": label, **shown}
            steps = params.get("steps", DEFAULT_STEPS)
            shown["steps"] = steps
            if self.piles and "seed" not in shown:
                shown["seed"] = 0
            out.append(
                {
                    "index": index,
                    "params": shown,
                    "scene_text": json.dumps(modified),
                    "scene_name": label if label != "inline" else f"{self.path or 'sweep'}: case {index}",
                    "base_dir": base_dir,
                    "steps": steps,
                    "broadphase": self.broadphase,
                    "trajectory": self.trajectory,
                    "fields": fields,
                }
            )
        return out


def load_sweep(path: str) -> Sweep:
    """Reads and checks a sweep file (``.json``, or ``.yaml``/``.yml``). Raises SweepError."""
    return Sweep(_read_document(path), path)


def sweep_from_scenes(scenes: list, steps: int | None = None, base_dir: str | None = None) -> Sweep:
    """A sweep that runs each scene (a path or a scene object) once, in order."""
    doc: dict = {"cases": [{"scene": s} for s in scenes]}
    if steps is not None:
        doc["steps"] = steps
    return Sweep(doc, "", base_dir)
