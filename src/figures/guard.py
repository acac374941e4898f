"""How the figure scripts end when something goes wrong: one line, never a Python traceback (the user ran
`siloscope figures`, not Python). A refusal of the input (siloscope.SiloscopeError) exits 2 with its message;
anything else exits 1 naming the script and the failure, and asks for a report. SILOSCOPE_TRACEBACK=1 shows the
traceback for whoever mends it."""
import os
import sys


def guarded(script, main):
    try:
        main()
    except KeyboardInterrupt:
        sys.exit(130)
    except SystemExit:
        raise
    except Exception as e:  # noqa: BLE001  the last line of defence: one line instead of a traceback
        if os.environ.get("SILOSCOPE_TRACEBACK"):
            raise
        if type(e).__name__ == "SiloscopeError":
            print(f"{script}: {e}", file=sys.stderr)
            sys.exit(2)
        print(f"{script}: failed: {type(e).__name__}: {e} (a fault of siloscope's: please report it with the "
              f"command; SILOSCOPE_TRACEBACK=1 shows where)", file=sys.stderr)
        sys.exit(1)
