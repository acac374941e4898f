"""siloscope export --format gsd: TRAJECTORY OUT FIRST LAST X0 Y0 X1 Y1 (the binary calls this with the
container's box; src/python/siloscope/_gsd.py writes the file)."""
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "python"))
import siloscope  # noqa: E402
from siloscope._gsd import write_gsd  # noqa: E402
from guard import guarded  # noqa: E402  one line, never a traceback


def main():
    t = siloscope.read_trajectory(sys.argv[1])
    # The recording's contacts, when it kept them, as the frames' bonds (force chains in OVITO).
    beside = os.path.join(os.path.dirname(os.path.abspath(sys.argv[1])), "contacts.sscon")
    contacts = siloscope.read_contacts(beside, n_particles=t.n) if os.path.exists(beside) else None
    write_gsd(t, sys.argv[2], int(sys.argv[3]), int(sys.argv[4]), tuple(float(v) for v in sys.argv[5:9]),
              contacts=contacts)


if len(sys.argv) != 9:
    sys.exit(__doc__)
guarded("export_gsd", main)
