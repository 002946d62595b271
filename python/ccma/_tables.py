"""Tables of ccma's results: the CSV files the `ccma` tool writes, as NumPy columns.

A Table holds the columns of one CSV file of the tool (`ccma trajectory --out`,
`ccma plan --out`, `ccma workspace --out`, `ccma replay --out`'s end_effector.csv
and bases.csv) under the CSV's header names, in the CSV's order. Each column's
type follows from its name, the same for every table:

- flags (`reached`, `reachable`, `within_limits`, `torn`, `all_reached`,
  `feasible`, `converged`, `assembled`): NumPy bool (the CSV's 1 and 0);
- counts (`iterations`, `limits_violated`, `wave`, `start`, `steps`, `tile`):
  NumPy int64;
- text (`clearance_pair`, `limited_by`, `warning`): NumPy arrays of str (object
  dtype);
- every other column: NumPy float64, NaN where the CSV leaves the cell empty
  (a workspace sample's controls when it is unreachable, a row without a
  clearance).

`to_columns()` gives the columns (copies), `to_records()` one dict per row
(None for an empty cell), `to_dataframe()` a pandas DataFrame (pandas is
imported only then), `to_csv(path)` the tool's CSV file.
"""
import math
import os

import numpy as _np


def out_path(out):
    """The path `out=` names (os.fspath), None for None; ValueError when its folder does
    not exist, before anything is computed (as the command checks --out)."""
    if out is None:
        return None
    path = os.fspath(out)
    if not path or not os.path.isdir(os.path.dirname(path) or "."):
        raise ValueError("out: %r: its folder does not exist" % path[:256])
    return path

FLAG_COLUMNS = frozenset({"reached", "reachable", "within_limits", "torn", "all_reached", "feasible", "converged",
                          "assembled"})
COUNT_COLUMNS = frozenset({"iterations", "limits_violated", "wave", "start", "steps", "tile"})
TEXT_COLUMNS = frozenset({"clearance_pair", "limited_by", "warning"})


def _column(name, values):
    """`values` (a sequence or array) as the column type of `name`, read-only."""
    if name in TEXT_COLUMNS:
        array = _np.empty(len(values), dtype=object)
        array[:] = [str(v) for v in values]
    elif name in FLAG_COLUMNS:
        array = _np.array(values, dtype=bool)
    elif name in COUNT_COLUMNS:
        array = _np.array(values, dtype=_np.int64)
    else:
        array = _np.array(values, dtype=float)
    array.flags.writeable = False
    return array


def _cell(name, text, where):
    """One CSV cell of column `name` as the column's type (None when empty)."""
    if text == "":
        if name in TEXT_COLUMNS:
            return ""
        if name in FLAG_COLUMNS or name in COUNT_COLUMNS:
            raise ValueError("%s: column %r: an empty cell" % (where, name))
        return math.nan
    if name in TEXT_COLUMNS:
        return text
    if name in FLAG_COLUMNS:
        if text not in ("0", "1"):
            raise ValueError("%s: column %r: %r is not 0 or 1" % (where, name, text[:40]))
        return text == "1"
    if name in COUNT_COLUMNS:
        return int(text)
    return float(text)


def _format(value):
    """A cell as the tool writes it: 17 significant digits, 1/0, empty for NaN."""
    if isinstance(value, (bool, _np.bool_)):
        return "1" if value else "0"
    if isinstance(value, (int, _np.integer)):
        return str(int(value))
    if isinstance(value, (float, _np.floating)):
        return "" if not math.isfinite(value) else format(float(value), ".17g")
    return str(value)


class Table:
    """Columns of a CSV file of the `ccma` tool, by header name (see the module's doc
    for the column types). `table["reached"]`, `table.names`, `len(table)` (rows)."""

    def __init__(self, columns, text=None):
        self._columns = {str(name): _column(str(name), values) for name, values in columns.items()}
        rows = {len(c) for c in self._columns.values()}
        if len(rows) > 1:
            raise ValueError("Table: columns of different lengths %s" % sorted(rows))
        self._rows = rows.pop() if rows else 0
        self._text = text

    @classmethod
    def from_arrays(cls, columns):
        """The table of a command's columns as ccma builds them (documents/table.h): NumPy
        arrays already of their kind, by name, in order; kept read-only."""
        table = cls.__new__(cls)
        table._columns = {}
        for name, values in columns.items():
            array = _np.asarray(values, dtype=object) if isinstance(values, list) else _np.asarray(values)
            array.flags.writeable = False
            table._columns[str(name)] = array
        rows = {len(c) for c in table._columns.values()}
        if len(rows) > 1:
            raise ValueError("Table: columns of different lengths %s" % sorted(rows))
        table._rows = rows.pop() if rows else 0
        table._text = None
        return table

    @classmethod
    def from_csv(cls, text, source="<csv>", comment_lines=0):
        """The table of a CSV text as the tool writes it (after `comment_lines` lines)."""
        lines = text.splitlines()[comment_lines:]
        if not lines:
            raise ValueError("%s: no header" % source)
        names = lines[0].split(",")
        cells = [[] for _ in names]
        for number, line in enumerate(lines[1:], start=comment_lines + 2):
            values = line.split(",")
            if len(values) != len(names):
                raise ValueError("%s:%d: %d cells, the header has %d" % (source, number, len(values), len(names)))
            where = "%s:%d" % (source, number)
            for k, (name, value) in enumerate(zip(names, values)):
                cells[k].append(_cell(name, value, where))
        return cls(dict(zip(names, cells)), text=text)

    @property
    def names(self):
        """The column names, in the CSV's order."""
        return list(self._columns)

    def __getitem__(self, name):
        try:
            return self._columns[name]
        except KeyError:
            raise KeyError("no column %r; the columns are %s" % (name, ", ".join(self._columns))) from None

    def __contains__(self, name):
        return name in self._columns

    def __iter__(self):
        return iter(self._columns)

    def __len__(self):
        return self._rows

    def __eq__(self, other):
        """Same names in the same order and the same values (NaN equal to NaN)."""
        if not isinstance(other, Table):
            return NotImplemented
        if self.names != other.names or len(self) != len(other):
            return False
        for name, column in self._columns.items():
            theirs = other._columns[name]
            if column.dtype.kind == "f" or theirs.dtype.kind == "f":
                if not _np.array_equal(column, theirs, equal_nan=True):
                    return False
            elif column.tolist() != theirs.tolist():
                return False
        return True

    __hash__ = None

    def __repr__(self):
        shown = ", ".join(self.names[:6]) + (", ..." if len(self._columns) > 6 else "")
        return "<ccma.Table %d rows x %d columns: %s>" % (self._rows, len(self._columns), shown)

    def stack(self, names):
        """The named numeric columns side by side: an (rows x len(names)) float64 array."""
        return _np.column_stack([_np.asarray(self[n], dtype=float) for n in names]) if names else \
            _np.empty((self._rows, 0))

    def to_columns(self):
        """{name: NumPy array}, one writable copy per column, in the CSV's order."""
        return {name: column.copy() for name, column in self._columns.items()}

    def to_records(self):
        """One dict per row {name: value}: bool, int, float or str; None where the CSV cell is empty."""
        columns = [(name, column.tolist()) for name, column in self._columns.items()]
        records = []
        for i in range(self._rows):
            row = {}
            for name, values in columns:
                v = values[i]
                row[name] = None if isinstance(v, float) and math.isnan(v) else v
            records.append(row)
        return records

    def to_dataframe(self):
        """A pandas DataFrame of the columns (pandas is imported here, only when asked for)."""
        try:
            import pandas  # noqa: F401  (optional: Debian's python3-pandas)
        except ImportError as e:
            raise ImportError("ccma: to_dataframe() needs pandas (apt-get install python3-pandas, or pip install "
                              "pandas); to_columns() gives the same columns as NumPy arrays and to_records() "
                              "as one dict per row") from e
        return pandas.DataFrame(self.to_columns(), columns=self.names)

    def to_csv_text(self):
        """The CSV text: the tool's own text when the table was read from it, else the
        columns written as the tool writes them (17 significant digits, flags 1/0,
        empty cells for NaN)."""
        if self._text is not None:
            return self._text
        lines = [",".join(self._columns)]
        columns = [column.tolist() for column in self._columns.values()]
        for i in range(self._rows):
            lines.append(",".join(_format(values[i]) for values in columns))
        return "\n".join(lines) + "\n"

    def to_csv(self, path):
        """Writes the CSV file as the tool would (replaced atomically, never through a
        planted link); returns the path."""
        from .viewer import _write_replacing
        _write_replacing(path, self.to_csv_text().encode("utf-8"))
        return path
