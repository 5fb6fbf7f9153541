"""Scenes and sweeps from Python values to the JSON text of the scene layer.

The schema, its validation and its one-line messages are the scene layer's, shared with the
command line: rhabel.solve sends the scene as JSON text to the same parser
as ``rhabel solve``. What is Python's own is done here, before: any Mapping is an object and any
list, tuple or NumPy array an array; NumPy scalars are numbers; and what JSON cannot say is refused
with the path of the value: a key that is not a string, NaN, an infinity, or a value of another
type.
"""

import json
import math
import numbers
from collections.abc import Mapping

import numpy as np


_LARGEST = 1.7976931348623157e308  # the largest double


def _fail(message):
    raise ValueError(" ".join(str(message).split("\n")))


def _child(path, key):
    return f"{path}.{key}" if path else key


def _show(value):
    try:
        text = repr(value)
    except Exception:  # a hostile __repr__
        text = "?"
    return text if len(text) <= 40 else text[:37] + "..."


def _number(value, path):
    """An int or float (NumPy's too) as a JSON number; NaN and infinities refused."""
    if isinstance(value, numbers.Integral):
        if abs(int(value)) > _LARGEST:
            _fail(f"{path} = {_show(int(value))} overflows a double")
        return int(value)
    x = float(value)
    if math.isnan(x):
        _fail(f"{path} = nan is not a number")
    if math.isinf(x):
        _fail(f"{path} = {'+inf' if x > 0 else '-inf'} overflows a double")
    return x


def _array(value, path):
    """A NumPy array as a list (its numbers checked finite)."""
    if value.dtype.kind == "f" and not np.all(np.isfinite(value)):
        bad = int(np.flatnonzero(~np.isfinite(value.ravel()))[0])
        _number(float(value.ravel()[bad]), f"{path}[{bad}]")  # raises, naming the first
    if value.dtype.kind in "biuf":
        return value.tolist()
    return [_plain(v, f"{path}[{i}]") for i, v in enumerate(value.tolist())]


def _plain(value, path):
    """value as plain JSON data (dict, list, str, int, float, bool, None), or ValueError naming path."""
    kind = type(value)
    if kind is float:  # the common case first: a sample, a load
        if value - value != 0:  # NaN or an infinity
            return _number(value, path)
        return value
    if kind is str or kind is bool or value is None:
        return value
    if kind is int:
        return value if -_LARGEST <= value <= _LARGEST else _number(value, path)
    if isinstance(value, Mapping):
        out = {}
        for key, item in value.items():
            if not isinstance(key, str):
                _fail(f"{_child(path, repr(key))} is not a known field: keys must be strings")
            out[key] = _plain(item, _child(path, key))
        return out
    if isinstance(value, (list, tuple)):
        if all(type(v) is float for v in value):  # samples: checked in one pass
            if any(v - v != 0 for v in value):  # NaN or an infinity somewhere: name the first
                return [_plain(v, f"{path}[{i}]") for i, v in enumerate(value)]
            return list(value)
        return [_plain(v, f"{path}[{i}]") for i, v in enumerate(value)]
    if isinstance(value, np.ndarray):
        return _array(value, path)
    if isinstance(value, (bool, np.bool_)):
        return bool(value)
    if isinstance(value, numbers.Real):
        return _number(value, path)
    _fail(f"{path or 'the value'} = {_show(value)} is not a JSON value (type {kind.__name__})")


def _plain_json(value):
    """json.dumps' default: NumPy arrays and scalars (np.float64 is a float already) as Python data."""
    if isinstance(value, (np.ndarray, np.generic)):
        return value.tolist()
    raise TypeError


def _string_keys(value, depth=0):
    """Whether json.dumps may take value as it is: every key of every Mapping a string (json.dumps
    would turn 1 into "1") and every int within the double range (the walk names the others)."""
    if depth > 64:
        return False  # deep: the walk of _plain decides (and names the limit)
    if isinstance(value, Mapping):
        return all(type(k) is str and _string_keys(v, depth + 1) for k, v in value.items())
    if type(value) in (list, tuple):
        return all(type(v) in (float, str) or _string_keys(v, depth + 1) for v in value)
    if type(value) is int:
        return -_LARGEST <= value <= _LARGEST
    return True


def json_text(value, what):
    """A scene or a sweep (what: "scene" or "sweep") as the JSON text of the scene layer; a value
    JSON has not is a ValueError naming its path (in a sweep, after "sweep: ")."""
    if not isinstance(value, Mapping):
        kind = "an array" if isinstance(value, (list, tuple)) else f"a {type(value).__name__}"
        _fail(f"{what}: the top level must be a JSON object {{...}} (a dict), got {kind}")
    if type(value) is dict and _string_keys(value):
        # The common case at json.dumps' speed; NaN, an infinity or a value JSON has not goes to
        # the walk below, which names its path.
        try:
            return json.dumps(value, allow_nan=False, default=_plain_json)
        except (ValueError, TypeError, OverflowError):
            pass
    try:
        return json.dumps(_plain(value, ""), allow_nan=False)
    except ValueError as e:
        if what == "scene":
            raise
        raise ValueError(f"{what}: {e}") from None
    except RecursionError:
        _fail(f"{what}: nested deeper than the interpreter's recursion limit")
