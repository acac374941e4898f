"""The `siloscope` command pip installs: the binary installed inside the package (siloscope/bin/siloscope)."""
import os
import sys


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    binary = os.path.join(here, "bin", "siloscope")
    if not os.access(binary, os.X_OK):
        sys.exit(f"siloscope: no binary at {binary} (this package was not installed with pip install ./)")
    os.execv(binary, [binary] + sys.argv[1:])
