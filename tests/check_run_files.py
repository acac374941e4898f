#!/usr/bin/env python3
"""A run's files are opened by one module: the names of a run directory's files (metadata.toml,
trajectory.sstraj, contacts.sscon and the event tables) appear as string literals in src/ only in io/run.h,
where they are named once (io::run_file), and core/scene.h (every output's metadata file). Every other file
reaches them through io::Run or those names, so every reader gets the same checks.

    python3 tests/check_run_files.py SRC_DIR     (exit 1 and the offending lines listed when any)"""
import os
import re
import sys

NAMES = ("metadata.toml", "trajectory.sstraj", "contacts.sscon", "exits.csv", "clogs.csv", "arches.csv",
         "clog_arches.csv")
ALLOWED = {os.path.join("io", "run.h"), os.path.join("core", "scene.h")}


def main(src):
    found = []
    literal = re.compile(r'"(' + "|".join(re.escape(n) for n in NAMES) + r')"')
    for root, _dirs, files in os.walk(src):
        for name in files:
            if not name.endswith((".cpp", ".h")):
                continue
            path = os.path.join(root, name)
            rel = os.path.relpath(path, src)
            if rel in ALLOWED:
                continue
            for k, line in enumerate(open(path, encoding="utf-8"), 1):
                code = line.split("//")[0]
                m = literal.search(code)
                if m:
                    found.append(f"{rel}:{k}: names {m.group(1)} (use io::run_file or io::Run)")
    for f in found:
        print(f)
    if found:
        sys.exit(1)
    print("run files: named in io/run.h only")


if __name__ == "__main__":
    main(sys.argv[1])
