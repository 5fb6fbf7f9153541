"""Record: the dict-like result type of rhabel.solve (keys readable as attributes)."""

import json

import numpy as np


class Record(dict):
    """A dict whose keys are also attributes: ``r.indentors[0].contact_length`` is
    ``r["indentors"][0]["contact_length"]``. Nested dicts are Records, lists stay lists, sampled
    fields are NumPy arrays. ``to_json()`` gives the command line's JSON document."""

    __slots__ = ()

    def __getattr__(self, name):
        try:
            return self[name]
        except KeyError:
            raise AttributeError(
                f"{name!r} is not a field of this result (fields: {', '.join(self)})") from None

    def __dir__(self):
        return list(self) + list(super().__dir__())

    def to_plain(self):
        """The same content as plain dicts, lists and floats (arrays become lists, tuples lists):
        what ``json.loads`` of the command line's output gives."""
        return _plain(self)

    def to_json(self, **kwargs):
        """JSON text of the result (``json.dumps`` keyword arguments pass through). Raises
        ValueError on NaN (e.g. ``residual=False``), as the command line never prints NaN."""
        kwargs.setdefault("allow_nan", False)
        return json.dumps(_plain(self), **kwargs)


def _plain(value):
    if isinstance(value, dict):
        return {k: _plain(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [_plain(v) for v in value]
    if isinstance(value, np.ndarray):
        return value.tolist()
    if isinstance(value, np.generic):
        return value.item()
    return value
