"""CSV tables as pandas DataFrames, checked: the header, and the columns that must hold whole numbers >= 0 or
finite numbers. One reader for the package and the figure scripts."""
import math
import os

import numpy as np

from ._errors import SiloscopeError
from ._manifest import verify_listed

# The most bytes any table siloscope writes may hold (a 10^6-exit run is ~30 MB): an input that is a device or
# grows without end is refused instead of read.
MAX_TABLE_BYTES = 1 << 30


def regular_file(path, what):
    """The path of a regular file of bounded size (links resolved), or a SiloscopeError saying what it is."""
    real = os.path.realpath(path)
    if not os.path.exists(real):
        raise SiloscopeError(f"{path}: no such {what}")
    if os.path.isdir(real):
        raise SiloscopeError(f"{path} is a directory, not a {what}")
    if not os.path.isfile(real):
        raise SiloscopeError(f"{path}: a {what} must be a regular file (this is a device, pipe or socket)")
    size = os.path.getsize(real)
    if size > MAX_TABLE_BYTES:
        raise SiloscopeError(f"{path}: {size} bytes is too large for a {what}")
    return real


def read_table(path, first_columns=(), counts=(), finite=(), optional=False, nonnegative=(), fractions=()):
    """The CSV at `path` as a DataFrame. `first_columns`: the header must start with these; `counts`: columns of
    whole numbers >= 0; `finite`: columns that may not hold NaN or infinity; `nonnegative`: finite numbers >= 0
    (NaN allowed: not measured), `fractions`: numbers in [0, 1] (NaN allowed), each checked where the column
    exists.
    optional: None if the file is absent."""
    import pandas as pd  # on first use: `import siloscope` does not pay for pandas
    if optional and not os.path.exists(path):
        return None
    regular_file(path, "table")
    verify_listed(path)
    with open(path, "rb") as f:
        data = f.read()
    if data and not data.endswith(b"\n"):
        raise SiloscopeError(f"{path}: truncated (the last line has no newline)")
    try:
        table = pd.read_csv(path, keep_default_na=False, na_values=["nan", "NaN", ""])
    except (pd.errors.ParserError, pd.errors.EmptyDataError, UnicodeDecodeError) as e:
        raise SiloscopeError(f"{path}: not a CSV table siloscope wrote ({str(e).splitlines()[0]})") from None
    header = list(table.columns)
    if list(header[: len(first_columns)]) != list(first_columns):
        raise SiloscopeError(f"{path}:1: header is '{','.join(header)}', expected it to start with "
                             f"'{','.join(first_columns)}'")
    for col in counts:
        if col not in table.columns:
            raise SiloscopeError(f"{path}: no column {col}")
        values = pd.to_numeric(table[col], errors="coerce")
        bad = ~(np.isfinite(values) & (values >= 0) & (values == np.floor(values)))
        if bad.any():
            row = int(np.flatnonzero(bad.to_numpy())[0])
            raise SiloscopeError(f"{path}:{row + 2}: {col} = {table[col].iloc[row]!r} is not a whole number >= 0")
        table[col] = values.astype(np.int64)
    for col, low, high, what in ([(c, 0.0, math.inf, "a finite number >= 0") for c in nonnegative] +
                                 [(c, 0.0, 1.0, "a fraction from 0 to 1") for c in fractions]):
        if col not in table.columns:
            continue
        values = pd.to_numeric(table[col], errors="coerce").to_numpy(dtype=float)
        raw = table[col].astype(str).str.strip().str.lower()
        bad = ~np.isnan(values) & ~((values >= low) & (values <= high) & np.isfinite(values))
        bad |= np.isnan(values) & ~raw.isin(["nan", ""]).to_numpy()  # text that is not a number
        if bad.any():
            row = int(np.flatnonzero(bad)[0])
            raise SiloscopeError(f"{path}:{row + 2}: {col} = {table[col].iloc[row]!r} is not {what}")
        table[col] = values
    for col in finite:
        if col not in table.columns:
            raise SiloscopeError(f"{path}: no column {col}")
        values = pd.to_numeric(table[col], errors="coerce")
        bad = ~np.isfinite(values.to_numpy(dtype=float))
        if bad.any():
            row = int(np.flatnonzero(bad)[0])
            raise SiloscopeError(f"{path}:{row + 2}: {col} = {table[col].iloc[row]!r} is not a finite number")
        table[col] = values
    return table


def records(table):
    """The rows of a table as dicts of plain Python values (floats where numbers), for scripts that loop."""
    out = []
    for row in table.to_dict("records"):
        out.append({k: (float(v) if isinstance(v, (int, float, np.integer, np.floating)) and not isinstance(v, bool)
                        else v) for k, v in row.items()})
    return out


def finite_number(x):
    return isinstance(x, float) and math.isfinite(x)
