"""Where the grains of a campaign's realizations left: each finished realization's exit direction from its
metadata.toml ([run] exit_direction_deg, recorded from siloscope 0.2.0 on), as a table beside a pack whose runs
were made before (a rerun at the same seeds gives the same events, and adds the direction).

    python3 docs/campaigns/exit_directions.py RESULTS OUT.csv [KEY ...]     e.g. KEY = aperture tilt
"""
import glob
import os
import sys
import tomllib


def main(results, out, keys):
    rows = []
    for meta in sorted(glob.glob(os.path.join(results, "runs", "p*", "r*", "metadata.toml"))):
        with open(meta, "rb") as f:
            m = tomllib.load(f)
        run = m.get("run", {})
        if "exit_direction_deg" not in run:
            continue
        scene = m["scene"]
        rows.append([str(scene[k]) for k in keys] + [str(scene["seed"]), repr(run["exit_direction_deg"]),
                                                     repr(run.get("exit_angle_sd_deg", float("nan"))),
                                                     str(run["exit_direction_exits"])])
    if not rows:
        sys.exit(f"exit_directions.py: no realization under {results}/runs records its exit direction")
    tmp = out + ".partial"
    with open(tmp, "w") as f:
        f.write(",".join(list(keys) + ["seed", "exit_direction_deg", "exit_angle_sd_deg", "exits"]) + "\n")
        for r in rows:
            f.write(",".join(r) + "\n")
    os.replace(tmp, out)
    print(f"{len(rows)} realizations -> {out}")


if __name__ == "__main__":
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2], sys.argv[3:])
