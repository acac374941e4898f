"""trackpy's HDF5 tracks as CSV, for `siloscope import TRACKS.h5` (run by it; needs Debian's python3-pandas and
python3-tables).

trackpy writes its features and tracks with pandas (`PandasHDFStore`: one table per frame under the store, or
`PandasHDFStoreBig` and `df.to_hdf(...)`: one table); every table of the file is copied, in key order, a slice at a
time, so the CSV is written in memory that does not grow with the film.

    python3 _trackpy_hdf5.py TRACKS.h5 OUT.csv
"""
import sys


def main(argv):
    if len(argv) != 3:
        print("usage: _trackpy_hdf5.py TRACKS.h5 OUT.csv", file=sys.stderr)
        return 2
    try:
        import pandas as pd
        import tables  # noqa: F401  (pandas reads HDF5 through PyTables)
    except ImportError as e:
        print(f"needs python3-pandas and python3-tables (Debian): {e}", file=sys.stderr)
        return 3
    source, out = argv[1], argv[2]
    try:
        store = pd.HDFStore(source, mode="r")
    except Exception as e:  # not HDF5, or not pandas' layout
        print(f"not an HDF5 file pandas can open ({type(e).__name__})", file=sys.stderr)
        return 4
    with store:
        # Per-frame tables in frame order (frame_2 before frame_10).
        def order(key):
            return [(0, int(p), "") if p.isdigit() else (1, 0, p) for p in key.replace("_", "/").split("/")]

        keys = sorted(store.keys(), key=order)
        if not keys:
            print("holds no table (trackpy writes its tracks as pandas tables)", file=sys.stderr)
            return 4
        header = True
        with open(out, "w", newline="") as f:
            for key in keys:
                storer = store.get_storer(key)
                if getattr(storer, "is_table", False):
                    parts = store.select(key, chunksize=200000)
                else:
                    parts = [store.get(key)]
                for part in parts:
                    part.to_csv(f, header=header, index=False)
                    header = False
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
