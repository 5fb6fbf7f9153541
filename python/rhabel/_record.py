"""Record: the dict-like result type of rhabel.solve (keys readable as attributes), and Result,
the Record of a whole solve with a one-line-per-contact repr."""

import json

import numpy as np

# A Record's repr shows at most this many leading and trailing entries of an array (NumPy's
# summarisation), so that it stays short whatever the grid.
_REPR_ARRAY_EDGE = 3
# A Result's repr has one line per contact, at most this many (then one line saying how many more).
_REPR_MAX_CONTACTS = 20


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

    def __repr__(self):
        # Sampled fields are summarised (first and last entries), as NumPy does for long arrays.
        with np.printoptions(threshold=2 * _REPR_ARRAY_EDGE, edgeitems=_REPR_ARRAY_EDGE):
            return f"{type(self).__name__}({dict.__repr__(self)})"

    def to_dict(self):
        """The same content as plain Python data: nested dicts (not Records), lists, tuples,
        floats, ints, strings, None and booleans, with the sampled fields as the same NumPy arrays
        (not copies). ``to_plain()`` turns the arrays into lists as well."""
        return _plain(self, keep_arrays=True)

    def to_plain(self):
        """The same content as plain dicts, lists and floats (arrays become lists, tuples lists):
        what ``json.loads`` of the command line's output gives."""
        return _plain(self)

    def to_json(self, **kwargs):
        """JSON text of the result (``json.dumps`` keyword arguments pass through). Raises
        ValueError on NaN (e.g. ``residual=False``), as the command line never prints NaN."""
        kwargs.setdefault("allow_nan", False)
        return json.dumps(_plain(self), **kwargs)


def _plain(value, keep_arrays=False):
    """Records as dicts; lists and tuples as lists (keep_arrays: tuples stay tuples); NumPy arrays as
    lists (keep_arrays: the arrays themselves); NumPy scalars as Python numbers."""
    if isinstance(value, dict):
        return {k: _plain(v, keep_arrays) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        items = [_plain(v, keep_arrays) for v in value]
        return tuple(items) if keep_arrays and isinstance(value, tuple) else items
    if isinstance(value, np.ndarray):
        return value if keep_arrays else value.tolist()
    if isinstance(value, np.generic):
        return value.item()
    return value


class Contact(Record):
    """The Record of one contact (an indentor's, or a contact of a sampled profile), with its
    solved pressure as a function: ``pressure_at(x)``."""

    __slots__ = ("_pressure",)

    def pressure_at(self, x):
        """The solved contact pressure p(x) [Pa] at any abscissae x (a float, or any array-like:
        an array of the same shape), evaluated from the solution itself (its spectral density),
        not interpolated from samples: equal to the ``pressure`` samples at their abscissae (to
        rounding), 0 outside the open contact interval, +inf at a singular point inside (a wedge's
        apex below the boundary). Accuracy: the density's, ``error_estimate`` relative to the peak
        (an estimate). ValueError for a non-finite x. Releases the GIL."""
        field = getattr(self, "_pressure", None)
        if field is None:
            raise RuntimeError("pressure_at: this contact was unpickled or built from plain data: the solution "
                               "behind pressure_at stays in the process that solved it")
        xs = np.asarray(x, dtype=float)
        p = field(np.ascontiguousarray(xs.ravel())).reshape(xs.shape)
        return float(p) if xs.ndim == 0 else p

    def __reduce__(self):
        # Pickled (to another process): the data, without the solution behind pressure_at.
        return (Contact, (dict(self),))

    def __copy__(self):
        return self._copy(dict(self))

    def __deepcopy__(self, memo):
        import copy
        return self._copy(copy.deepcopy(dict(self), memo))

    def _copy(self, data):
        out = Contact(data)
        field = getattr(self, "_pressure", None)
        if field is not None:
            out._pressure = field  # immutable: copies share it
        return out


class Result(Record):
    """The result of rhabel.solve: a Record (a dict whose keys are also attributes) whose repr is
    a short summary, one line for the solve and one per contact (interval, load, C_f, status), at
    most _REPR_MAX_CONTACTS of them, whatever the grid. ``to_dict()``, ``to_plain()`` and
    ``to_json()`` give the whole content."""

    __slots__ = ()

    def __repr__(self):
        if "patches" in self:
            return self._patches_repr()
        contacts = self.get("indentors", self.get("contacts", []))
        diagnostics = self.get("diagnostics", {})
        head = (f"rhabel.Result: {len(contacts)} contact{'s' if len(contacts) != 1 else ''}, "
                f"status {diagnostics.get('status', '?')}, residual {_g(diagnostics.get('residual'))}, "
                f"regime {self.get('regime', '?')}, beta {_g(self.get('beta'))}, kappa {_g(self.get('kappa'))}")
        lines = [head]
        shown = contacts if len(contacts) <= _REPR_MAX_CONTACTS else contacts[:_REPR_MAX_CONTACTS - 1]
        for i, c in enumerate(shown):
            a, b = c.get("contact", (float("nan"), float("nan")))
            label = str(c.get("name") or c.get("shape") or "contact")[:24]
            lines.append(f"  [{i}] {label}: [{_g(a)}, {_g(b)}], load {_g(c.get('load'))}, "
                         f"C_f {_g(c.get('hysteretic_friction'))}, status {c.get('status', '?')}")
        if len(shown) < len(contacts):
            lines.append(f"  ... {len(contacts) - len(shown)} more (r.{'indentors' if 'indentors' in self else 'contacts'})")
        return "\n".join(lines)

    def _patches_repr(self):
        """A profile solved by the boundary-element method: C_f and contact fraction with their error
        estimates, then one line per patch."""
        patches = self["patches"]
        diagnostics = self.get("diagnostics", {})
        cf, fraction = self.get("hysteretic_friction", {}), self.get("contact_fraction", {})
        lines = [f"rhabel.Result: {len(patches)} patch{'es' if len(patches) != 1 else ''}, "
                 f"status {diagnostics.get('status', '?')}, C_f {_g(cf.get('value'))} +- {_g(cf.get('error'))}, "
                 f"contact fraction {_g(fraction.get('value'))} +- {_g(fraction.get('error'))}, "
                 f"{diagnostics.get('panels', '?')} panels"]
        shown = patches if len(patches) <= _REPR_MAX_CONTACTS else patches[:_REPR_MAX_CONTACTS - 1]
        for i, p in enumerate(shown):
            a, b = p.get("contact", (float("nan"), float("nan")))
            lines.append(f"  [{i}] [{_g(a)}, {_g(b)}], load {_g(p['load']['value'])}, "
                         f"C_f {_g(p['hysteretic_friction']['value'])}")
        if len(shown) < len(patches):
            lines.append(f"  ... {len(patches) - len(shown)} more (r.patches)")
        return "\n".join(lines)


def _g(x):
    """A number in 6 significant digits (or '?' when absent)."""
    if x is None:
        return "?"
    try:
        return f"{float(x):.6g}"
    except (TypeError, ValueError):
        return str(x)
