"""The base of ccma's result objects: one name per concept, the tool's.

Every analysis of the Python API returns a result whose attributes are the keys
of the JSON document the `ccma` command prints for the same analysis (docs/cli.md),
with the same meaning and unit, and whose `to_dict()` is that document: the
same keys and values, flags as bool, numbers as int or float, arrays as
(nested) lists, a key the command leaves out left out. Attributes give the
same values in handier types: a list of numbers is a read-only NumPy array, an
object is a Record (attribute and item access, the same names).

A result that the command writes as a CSV file also has `table` (a
ccma.Table: the CSV's columns under its header names), `to_columns()`,
`to_records()`, `to_dataframe()` and `to_csv(path)`.
"""
import copy
import math
import warnings
from collections.abc import Mapping

import numpy as _np


def _number(v):
    return isinstance(v, (int, float)) and not isinstance(v, bool)


def _read_only(array):
    array.flags.writeable = False
    return array


def view(value):
    """A JSON value of the tool's output in the types of the Python API: an object
    as a Record, a list of numbers (null = NaN) or of equal-length number lists
    as a read-only float64 NumPy array (int64 when every entry is an int), a list
    of flags as a bool array, other lists element by element."""
    if isinstance(value, dict):
        return Record(value)
    if not isinstance(value, list) or not value:
        return value
    if all(isinstance(v, bool) for v in value):
        return _read_only(_np.array(value, dtype=bool))
    if all(_number(v) or v is None for v in value) and any(_number(v) for v in value):
        if all(isinstance(v, int) and not isinstance(v, bool) for v in value):
            return _read_only(_np.array(value, dtype=_np.int64))
        return _read_only(_np.array([math.nan if v is None else v for v in value], dtype=float))
    if all(isinstance(v, list) and v and all(_number(x) for x in v) for v in value) and \
            len({len(v) for v in value}) == 1:
        return _read_only(_np.array(value, dtype=float))
    return [view(v) for v in value]


class Record(Mapping):
    """An object of the tool's JSON output (a body, a joint, the clearance, ...):
    `r.name` or `r["name"]` (the JSON key), `r.keys()`, `r.to_dict()` (the JSON
    object itself). Values as for results: NumPy arrays for lists of numbers."""

    __slots__ = ("_data", "_views")

    def __init__(self, data):
        object.__setattr__(self, "_data", dict(data))
        object.__setattr__(self, "_views", {})

    def __getitem__(self, key):
        views = self._views
        if key not in views:
            views[key] = view(self._data[key])
        return views[key]

    def __getattr__(self, name):
        if name.startswith("_"):
            raise AttributeError(name)
        try:
            return self[name]
        except KeyError:
            raise AttributeError("no key %r; the keys are %s" % (name, ", ".join(self._data))) from None

    def __setattr__(self, name, value):
        raise AttributeError("a ccma.Record is read-only")

    def __iter__(self):
        return iter(self._data)

    def __len__(self):
        return len(self._data)

    def __eq__(self, other):
        if isinstance(other, Record):
            return self._data == other._data
        if isinstance(other, dict):
            return self._data == other
        return NotImplemented

    __hash__ = None

    def to_dict(self):
        """The JSON object (a deep copy): lists, not arrays."""
        return copy.deepcopy(self._data)

    def __repr__(self):
        return "Record(%r)" % (self._data,)


class Field(property):
    """An attribute of a result: the value of the JSON key `key`."""

    def __init__(self, key, doc, absent=None):
        def get(result):
            return result._value(key, absent)
        super().__init__(get, doc=doc)
        self.key = key


class Result:
    """The base of ccma's results: attributes are the keys of the tool's JSON (a
    key the command leaves out is None, `warning` is '' then), `to_dict()` the
    JSON document itself. `result["key"]` gives the attribute of a JSON key with a
    DeprecationWarning (use `result.key`); a key whose values are in the table raises
    KeyError naming where they are."""

    _main_table = None  # the name of the table `table` and to_* use, if any
    _elsewhere = {}     # item keys that are no JSON key of this result: where their values are

    def __init__(self, document, tables=None, **extras):
        self._document = document
        self._tables = dict(tables or {})
        self._views = {}
        for name, value in extras.items():
            setattr(self, "_" + name, value)

    @classmethod
    def json_keys(cls):
        """The JSON keys this result may carry, in the order of its attributes."""
        out = []
        for klass in reversed(cls.__mro__):
            for value in vars(klass).values():
                if isinstance(value, Field) and value.key not in out:
                    out.append(value.key)
        return out

    def _value(self, key, absent):
        if key not in self._document:
            return absent
        if key not in self._views:
            self._views[key] = view(self._document[key])
        return self._views[key]

    def to_dict(self):
        """The JSON document the `ccma` command prints (a deep copy)."""
        return copy.deepcopy(self._document)

    def __getitem__(self, key):
        if key in self._elsewhere:
            raise KeyError("%s[%r]: %s" % (type(self).__name__, key, self._elsewhere[key]))
        if key not in self.json_keys():
            raise KeyError(key)
        warnings.warn("%s[%r] is deprecated: use the attribute %s.%s (the JSON key of `ccma`)"
                      % (type(self).__name__, key, "result", key), DeprecationWarning, stacklevel=2)
        return getattr(self, key)

    # ---- tables (results the command also writes as CSV)
    @property
    def tables(self):
        """{name: ccma.Table}: the CSV files the command writes, by file name without `.csv`."""
        return dict(self._tables)

    def _table(self, name):
        name = self._main_table if name is None else name
        if name not in self._tables:
            raise KeyError("%s has no table %r (tables: %s)" % (type(self).__name__, name, ", ".join(self._tables)))
        return self._tables[name]

    def to_columns(self, table=None):
        """The table's columns {CSV header name: NumPy array} (copies)."""
        return self._table(table).to_columns()

    def to_records(self, table=None):
        """The table as one dict per row (None where the CSV cell is empty)."""
        return self._table(table).to_records()

    def to_dataframe(self, table=None):
        """The table as a pandas DataFrame (needs pandas; ImportError says so)."""
        return self._table(table).to_dataframe()

    def to_csv(self, path, table=None):
        """Writes the table as the command's CSV file; returns the path."""
        return self._table(table).to_csv(path)

    def __repr__(self):
        shown = []
        for key in ("model", "converged", "assembled", "used", "samples", "reachable", "steps", "out"):
            if key in self._document and not isinstance(self._document[key], (list, dict)):
                shown.append("%s=%r" % (key, self._document[key]))
        if self._tables:
            shown.append("tables=%s" % ",".join("%s[%d]" % (n, len(t)) for n, t in self._tables.items()))
        return "<ccma.%s %s>" % (type(self).__name__, " ".join(shown))
