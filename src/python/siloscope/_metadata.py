"""metadata.toml: siloscope's record of a run (version, command, every scene key, derived facts, health)."""
import tomllib

from ._errors import SiloscopeError
from ._manifest import verify_listed
from ._tables import regular_file


def read_metadata(path):
    real = regular_file(path, "metadata file")
    verify_listed(path)
    try:
        with open(real, "rb") as f:
            meta = tomllib.load(f)
    except (tomllib.TOMLDecodeError, UnicodeDecodeError) as e:
        raise SiloscopeError(f"{path}: malformed TOML ({e})") from None
    return check_metadata(meta, path)


def check_metadata(meta, where):
    for table, key in (("siloscope", "version"), ("scene", "seed"), ("scene", "duration")):
        if key not in meta.get(table, {}):
            raise SiloscopeError(f"{where}: [{table}] has no {key} (a truncated or foreign metadata file)")
    if not meta["scene"]["duration"] > 0:
        raise SiloscopeError(f"{where}: [scene] duration = {meta['scene']['duration']} is not > 0")
    return meta


def species_of(scene):
    """The scene's species as (names, sides): its [[species]] tables, or the paper's two-species shorthand."""
    tables = scene.get("species")
    if not tables:
        return ["original", "added"], [0, 0]
    return [t["name"] for t in tables], [int(t.get("sides", 0)) for t in tables]
