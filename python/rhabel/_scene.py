"""Validation of a scene dict: the JSON scene schema of examples/README.md, with the policy and
the messages of the command line (the scene layer, scene/src/scene.cpp), so that a scene is accepted by
rhabel.solve exactly when `rhabel solve` accepts the same JSON, and a rejected one gets the same
one-line message (without the command line's "solve: " prefix; tests/python/test_errors.py
compares them).

Policy (as the command line): every field is required except ``apex``, ``name``,
``description``, ``material.name``, ``body`` and ``height`` (with a body, an indentor has no
``load`` and may have a ``height``; without one, no ``height``); unknown fields are errors (also a field of another shape,
e.g. ``radius`` on a wedge); numbers must be finite (ints and NumPy numbers are numbers, booleans
and strings are not). Python-only cases: keys must be strings, NaN is rejected like an
overflow, the scene and its objects may be any Mapping and ``indentors`` any list or tuple.
"""

import json
import math
import numbers
from collections.abc import Mapping

import numpy as np

from ._record import Record

_INF = math.inf


class _Range:
    def __init__(self, lo, hi, lo_open, hi_open, text):
        self.lo, self.hi, self.lo_open, self.hi_open, self.text = lo, hi, lo_open, hi_open, text

    def __contains__(self, x):
        return ((x > self.lo) if self.lo_open else (x >= self.lo)) and (
            (x < self.hi) if self.hi_open else (x <= self.hi))


_POSITIVE = _Range(0, _INF, True, True, "(0, inf)")
_NON_NEGATIVE = _Range(0, _INF, False, True, "[0, inf)")
_ANY_FINITE = _Range(-_INF, _INF, True, True, "(-inf, inf)")
_ALPHA = _Range(0, 1, False, True, "[0, 1)")
_POISSON = _Range(0, 0.5, False, False, "[0, 0.5]")
_MAX_PANELS = _Range(256, 8388608, False, False, "[256, 8388608]")

SHAPES = {
    "parabolic": ("radius",),
    "wedge": ("slope_leading", "slope_trailing"),
    "flat": ("width",),
}


def _fail(message):
    raise ValueError(" ".join(str(message).split("\n")))


def _type_of(value):
    if value is None:
        return "null"
    if isinstance(value, (bool, np.bool_)):
        return "a boolean"
    if isinstance(value, str):
        return "a string"
    if isinstance(value, (list, tuple)):
        return "an array"
    if isinstance(value, Mapping):
        return "an object"
    if _is_number(value):
        return "a number"
    return "a " + type(value).__name__


def _show(value):
    if _is_number(value):
        if isinstance(value, numbers.Integral):
            text = str(int(value))
        else:
            x = float(value)
            text = "nan" if math.isnan(x) else ("+inf" if x > 0 else "-inf") if math.isinf(x) else repr(x)
    else:
        try:
            text = json.dumps(value, separators=(",", ":"), ensure_ascii=False)  # as nlohmann's dump()
        except RecursionError:  # nested deeper than the interpreter's recursion limit
            text = "[...]" if isinstance(value, (list, tuple)) else "{...}"
        except (TypeError, ValueError):
            try:
                text = repr(value)
            except RecursionError:
                text = "..."
    return text if len(text) <= 40 else text[:37] + "..."


def _is_number(value):
    if type(value) in (float, int):  # the common case, without the slower ABC check
        return True
    return isinstance(value, numbers.Real) and not isinstance(value, (bool, np.bool_))


def _child(parent, key):
    return f"{parent}.{key}" if parent else key


def _only_keys(obj, path, allowed, context=""):
    for key in obj:
        if not isinstance(key, str):
            _fail(f"{_child(path, repr(key))} is not a known field{context}: keys must be strings "
                  f"(known: {', '.join(allowed)})")
        if key not in allowed:
            _fail(f"{_child(path, key)} is not a known field{context} (known: {', '.join(allowed)})")


def _require(obj, path, key, what):
    if key not in obj:
        _fail(f"{_child(path, key)} is missing: {what}")
    return obj[key]


def _number(value, path, valid, what):
    if type(value) is float and value in valid:  # fast path: a finite float in range (inf is in no range)
        return value
    if not _is_number(value):
        _fail(f"{path} must be a number in {valid.text} ({what}), got {_type_of(value)} {_show(value)}")
    try:
        x = float(value)
    except OverflowError:
        _fail(f"{path} = {_show(value)} overflows a double; valid range {valid.text} ({what})")
    if math.isinf(x):
        _fail(f"{path} = {_show(value)} overflows a double; valid range {valid.text} ({what})")
    if math.isnan(x):
        _fail(f"{path} = nan is not a number; valid range {valid.text} ({what})")
    if x not in valid:
        _fail(f"{path} = {_show(value)} is outside the valid range {valid.text} ({what})")
    return x


def _required_number(obj, path, key, valid, what):
    if key not in obj:
        _fail(f"{_child(path, key)} is missing: a number in {valid.text} is required ({what})")
    value = obj[key]
    if type(value) is float and value in valid:  # fast path, as in _number
        return value
    return _number(value, _child(path, key), valid, what)


def _optional_string(obj, path, key):
    if key not in obj:
        return None
    value = obj[key]
    if not isinstance(value, str):
        _fail(f"{_child(path, key)} must be a string, got {_type_of(value)} {_show(value)}")
    return value


def _require_object(value, path):
    if not isinstance(value, Mapping):
        _fail(f"{path} must be a JSON object {{...}}, got {_type_of(value)} {_show(value)}")


def _material(value):
    path = "material"
    _require_object(value, path)
    _only_keys(value, path, ("alpha", "E1", "nu", "coulomb", "name"))
    m = Record({
        "alpha": _required_number(value, path, "alpha", _ALPHA, "power-law exponent of E(t) = E1 t^-alpha"),
        "E1": _required_number(value, path, "E1", _POSITIVE, "modulus coefficient of E(t) = E1 t^-alpha"),
        "nu": _required_number(value, path, "nu", _POISSON, "Poisson ratio"),
        "coulomb": _required_number(value, path, "coulomb", _NON_NEGATIVE, "Coulomb friction coefficient"),
    })
    name = _optional_string(value, path, "name")
    if name:
        m["name"] = name
    return m


_WHAT = {
    "radius": "radius of curvature of the parabola",
    "slope_leading": "slope of the face at x < apex",
    "slope_trailing": "slope of the face at x > apex",
    "width": "width of the flat face",
}


def _indentor(value, path, body):
    _require_object(value, path)
    shape = _require(value, path, "shape", 'one of "parabolic", "wedge", "flat" is required')
    if not isinstance(shape, str):
        _fail(f'{_child(path, "shape")} must be one of "parabolic", "wedge", "flat", got '
              f"{_type_of(shape)} {_show(shape)}")
    if shape not in SHAPES:
        _fail(f'{_child(path, "shape")} = {_show(shape)} is not a known shape '
              '(valid: "parabolic", "wedge", "flat")')
    geometry = SHAPES[shape]
    if body and "load" in value:
        _fail(f"{_child(path, 'load')} is not used on a rigid body (the body's load is split over the "
              "indentors): remove it")
    if not body and "height" in value:
        _fail(f'{_child(path, "height")} needs a rigid body ("body": {{"load": ...}}): remove it or add the body')
    own = ("shape", "height", "apex", "name") if body else ("shape", "load", "apex", "name")
    _only_keys(value, path, own + geometry, f' for shape "{shape}"')
    d = Record(shape=shape)
    for key in geometry:
        d[key] = _required_number(value, path, key, _POSITIVE, _WHAT[key])
    if body:
        d["height"] = (_number(value["height"], _child(path, "height"), _ANY_FINITE, "height of the apex on the body")
                       if "height" in value else 0.0)
    else:
        d["load"] = _required_number(value, path, "load", _POSITIVE, "normal force per unit length")
    d["apex"] = _number(value["apex"], _child(path, "apex"), _ANY_FINITE, "apex position") if "apex" in value else 0.0
    name = _optional_string(value, path, "name")
    if name:  # the command line's echo: shape, name, geometry, load, apex
        d = Record({"shape": shape, "name": name, **{k: v for k, v in d.items() if k != "shape"}})
    return d


def _number_array(value, path, what):
    if isinstance(value, np.ndarray):
        value = value.tolist()
    if not isinstance(value, (list, tuple)):
        _fail(f"{path} must be an array of numbers ({what}), got {_type_of(value)} {_show(value)}")
    return [_number(v, f"{path}[{i}]", _ANY_FINITE, what) for i, v in enumerate(value)]


# The size limit of a profile CSV, as the command line's (rhabel/materials/text_file.hpp,
# max_text_file_bytes: 256 MiB, far above a realistic profile, bounds the memory a wrong path takes).
_MAX_TEXT_FILE_BYTES = 256 << 20


def _read_profile_csv(path, shown):
    """The two-column CSV of a profile, as the command line reads it (scene/src/scene.cpp)."""
    import os
    if "\0" in path or not os.path.isfile(path):  # only a regular file: a device or a pipe would be read forever
        _fail(f'profile.file = "{shown}" is not a readable regular file ({path!r})')
    if os.path.getsize(path) > _MAX_TEXT_FILE_BYTES:
        _fail(f'profile.file = "{shown}" is larger than the limit of {_MAX_TEXT_FILE_BYTES} bytes')
    try:
        # utf-8-sig: a byte-order mark at the start is skipped, the rule of every CSV rhabel reads
        with open(path, encoding="utf-8-sig") as f:
            lines = f.read().split("\n")
    except OSError:
        _fail(f'profile.file = "{shown}" cannot be read ({path})')
    x, z = [], []
    for number, line in enumerate(lines, start=1):
        stripped = line.strip(" \t\r")
        if not stripped or stripped.startswith("#"):
            continue
        fields = line
        for c in ",;\t\r":
            fields = fields.replace(c, " ")
        parts = fields.split()
        try:
            values = [float(v) for v in parts[:2]]
            numeric = len(values) == 2
        except ValueError:
            numeric = False
        if not numeric and not x and number == 1:
            continue  # a header
        if not numeric or len(parts) != 2 or not all(math.isfinite(v) for v in values):
            _fail(f'profile.file = "{shown}" line {number}: expected two finite numbers x,z, got "{line[:80]}"')
        x.append(values[0])
        z.append(values[1])
    return x, z


def _profile(value):
    _require_object(value, "profile")
    out = Record()
    if "file" in value:
        _only_keys(value, "profile", ("file", "corners", "period", "solver", "max_panels"), " with a file")
        out["file"] = _optional_string(value, "profile", "file")
        out["x"], out["z"] = _read_profile_csv(out["file"], out["file"])
    else:
        _only_keys(value, "profile", ("x", "z", "corners", "period", "solver", "max_panels"))
        out["x"] = _number_array(_require(value, "profile", "x", 'the sample abscissae (or "file")'), "profile.x",
                                 "sample abscissa")
        out["z"] = _number_array(_require(value, "profile", "z", "the sample heights"), "profile.z", "sample height")
    out["corners"] = (_number_array(value["corners"], "profile.corners", "abscissa of a slope jump")
                      if "corners" in value else [])
    if "period" in value:
        out["period"] = _number(value["period"], "profile.period", _POSITIVE,
                                "the period: the samples lie in [x_0, x_0 + period)")
    # The solver: the spectral contact search (finite windows) or the boundary-element method
    # (finite or periodic; the only one for a period), as the command line decides.
    solver = _optional_string(value, "profile", "solver")
    if not solver:
        solver = "boundary_element" if "period" in out else "spectral"
    elif solver == "spectral":
        if "period" in out:
            _fail('profile.solver = "spectral" solves finite windows only; a profile.period needs "boundary_element" '
                  '(or no profile.solver)')
    elif solver != "boundary_element":
        _fail(f'profile.solver = "{solver[:40]}" is not a solver (known: spectral, boundary_element)')
    out["solver"] = solver
    if "max_panels" in value:
        if solver != "boundary_element":
            _fail('profile.max_panels bounds the grids of profile.solver "boundary_element"; the spectral solver has none')
        m = _number(value["max_panels"], "profile.max_panels", _MAX_PANELS,
                    "the finest grid's panels, ~130 bytes each; a whole number")
        if m != math.floor(m):
            _fail(f"profile.max_panels = {_show(value['max_panels'])} must be a whole number of panels")
        out["max_panels"] = int(m)
    return out


def validate(scene):
    """The validated scene: a new Record (dict) with every number a float in range, ``apex`` filled in,
    the optional strings kept when non-empty (the command line's echo of the scene). Raises
    ValueError with one line naming the field."""
    if not isinstance(scene, Mapping):
        _fail(f"scene: the top level must be a JSON object {{...}} (a dict), got {_type_of(scene)}")
    _only_keys(scene, "", ("description", "material", "speed", "body", "indentors", "profile"))
    out = Record()
    description = _optional_string(scene, "", "description")
    if description:
        out["description"] = description
    out["material"] = _material(_require(scene, "", "material", "an object {alpha, E1, nu, coulomb} is required"))
    out["speed"] = _required_number(scene, "", "speed", _POSITIVE, "sliding speed")
    body = "body" in scene
    if body:
        value = scene["body"]
        _require_object(value, "body")
        _only_keys(value, "body", ("load",))
        out["body"] = Record(load=_required_number(value, "body", "load", _POSITIVE, "total normal force per unit length"))
    if "profile" in scene:
        if "indentors" in scene:
            _fail("indentors and profile are exclusive: give one of them")
        if not body:
            _fail('profile needs a rigid body with its total load: add "body": {"load": ...}')
        out["profile"] = _profile(scene["profile"])
        return out
    items = _require(scene, "", "indentors", "a non-empty array of indentors is required")
    if not isinstance(items, (list, tuple)):
        _fail(f"indentors must be a non-empty array [...], got {_type_of(items)} {_show(items)}")
    if not items:
        _fail("indentors is empty: at least one indentor is required")
    out["indentors"] = [_indentor(item, f"indentors[{i}]", body) for i, item in enumerate(items)]
    return out
