#!/usr/bin/env python3
"""The Python API's reference (docs/python-api.md), made from the package's own docstrings: every public name of
`siloscope` and `siloscope.stats`, its signature and its docstring.

    PYTHONPATH=src/python python3 docs/reference/python_api.py [OUT.md]"""
import inspect
import os
import sys

import siloscope
import siloscope.stats


def entry(name, obj):
    try:
        sig = str(inspect.signature(obj))
    except (TypeError, ValueError):
        sig = ""
    doc = inspect.getdoc(obj) or "(no docstring)"
    out = [f"### `{name}{sig}`", "", doc, ""]
    if inspect.isclass(obj):
        for m, member in inspect.getmembers(obj):
            if m.startswith("_") or not (inspect.isfunction(member) or isinstance(member, property)):
                continue
            target = member.fget if isinstance(member, property) else member
            try:
                msig = "" if isinstance(member, property) else str(inspect.signature(target))
            except (TypeError, ValueError):
                msig = ""
            out += [f"- `{name}.{m}{msig}`: " + (inspect.getdoc(target) or "").split("\n\n")[0].replace("\n", " "), ]
        out.append("")
    return out


def main(path):
    lines = ["# Python API", "", "Made from the package's docstrings by `docs/reference/python_api.py`; "
             "[Python](python.md) tells how to use it.", "", "## siloscope", "",
             inspect.getdoc(siloscope) or "", ""]
    for name in siloscope.__all__:
        lines += entry(name, getattr(siloscope, name))
    lines += ["## siloscope.stats", "", inspect.getdoc(siloscope.stats) or "", ""]
    for name, obj in inspect.getmembers(siloscope.stats, inspect.isfunction):
        if not name.startswith("_") and obj.__module__ == "siloscope.stats":
            lines += entry(name, obj)
    with open(path, "w") as f:
        f.write("\n".join(lines).rstrip() + "\n")


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(os.path.abspath(__file__)), "..",
                                                             "python-api.md"))
