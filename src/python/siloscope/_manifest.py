"""manifest.toml: the files siloscope wrote into an output directory (name, bytes, FNV-1a 64 hash). The readers
check each file they read against it, as siloscope's own readers do (src/io/manifest.cpp): a file cut, edited
or copied from another run after siloscope wrote it is refused, naming it and what differs."""
import os
import tomllib

from ._errors import SiloscopeError
from ._native import checked, module_or_none

MANIFEST = "manifest.toml"
MAX_MANIFEST_BYTES = 16 << 20
# FNV-1a is a byte-by-byte loop; in Python it costs about 0.3 s per MB. With the compiled module the binary's own
# hash checks every file; without it, files above this size (trajectories) are checked by their size only here.
HASH_LIMIT_BYTES = 4 << 20


def _fnv(h, data):
    for b in data:
        h = ((h ^ b) * 0x100000001B3) & 0xFFFFFFFFFFFFFFFF
    return h


def fnv1a64(path):
    native = checked("file_hash", path)
    if native is not None:
        return native
    h = 0xCBF29CE484222325
    with open(path, "rb") as f:
        while chunk := f.read(1 << 16):
            h = _fnv(h, chunk)
    return f"{h:016x}"


def read_manifest(directory):
    """The manifest of `directory` as {name: (bytes, hash)}, or None when it has none."""
    p = os.path.join(directory, MANIFEST)
    if not os.path.lexists(p):
        return None
    if not os.path.isfile(p) or os.path.islink(p):
        raise SiloscopeError(f"{p}: not a regular file (a manifest is one)")
    if os.path.getsize(p) > MAX_MANIFEST_BYTES:
        raise SiloscopeError(f"{p}: larger than any manifest siloscope writes")
    with open(p, "rb") as f:
        raw = f.read()
    try:
        t = tomllib.loads(raw.decode())
    except (tomllib.TOMLDecodeError, UnicodeDecodeError) as e:
        raise SiloscopeError(f"{p}: malformed TOML ({e})") from None
    # Since the self line (the FNV-1a 64 of every byte before it) a manifest checks itself; older ones do not.
    if isinstance(t.get("self"), str):
        at = raw.rfind(b'\nself = "')
        if at < 0 or f"{_fnv(0xCBF29CE484222325, raw[:at + 1]):016x}" != t["self"]:
            raise SiloscopeError(f"{p}: the manifest itself was changed after siloscope wrote it (its own hash "
                                 "differs), so the files it lists cannot be checked against it")
    if not isinstance(t.get("kind"), str) or not isinstance(t.get("files"), list):
        raise SiloscopeError(f"{p}: no kind or files (truncated?)")
    out = {}
    for row in t["files"]:
        if not (isinstance(row, list) and len(row) == 3 and isinstance(row[0], str) and isinstance(row[1], int)
                and row[1] >= 0 and isinstance(row[2], str)):
            raise SiloscopeError(f"{p}: an entry of files is not [name, bytes, hash]")
        out[row[0]] = (row[1], row[2])
    return out


# What an output directory's metadata.toml says when its writer also wrote a manifest (src/io/manifest.h).
DECLARATION = b'\n[siloscope]\nmanifest = "manifest.toml"\n'


def declares_manifest(directory):
    """Whether `directory`'s metadata.toml says siloscope wrote a manifest beside it."""
    p = os.path.join(directory, "metadata.toml")
    if not os.path.isfile(p) or os.path.islink(p):
        return False
    with open(p, "rb") as f:
        return DECLARATION in f.read(4096)


def verify_listed(path):
    """Checks `path` against the manifest of its directory (or of the directory above: a campaign's analysis
    lists its files there); nothing when no manifest lists it and none is declared (outputs of versions before
    manifests). A manifest that the directory's metadata.toml declares but that is gone is an error."""
    directory = os.path.dirname(os.path.abspath(path))
    for _ in range(2):
        m = read_manifest(directory)
        if m is None and declares_manifest(directory):
            raise SiloscopeError(f"{path}: {os.path.join(directory, '')} has no manifest.toml, though its "
                                 "metadata.toml says siloscope wrote one (removed after?); what the output holds "
                                 "cannot be checked: make it again")
        if m is not None:
            name = os.path.relpath(os.path.abspath(path), directory).replace(os.sep, "/")
            if name in m:
                why = _mismatch(os.path.join(directory, name), name, *m[name])
                if why:
                    raise SiloscopeError(f"{path}: {why}")
            return
        directory = os.path.dirname(directory)


def _mismatch(path, name, size, digest):
    if not os.path.lexists(path):
        return f"{name} is missing (its manifest lists it)"
    if os.path.islink(path) or not os.path.isfile(path):
        return f"{name} is no longer a regular file"
    actual = os.path.getsize(path)
    if actual != size:
        return (f"{name} is {actual} bytes where its manifest says {size}" +
                (" (truncated?)" if actual < size else " (changed after siloscope wrote it)"))
    if (actual <= HASH_LIMIT_BYTES or module_or_none() is not None) and fnv1a64(path) != digest:
        return f"{name} differs from what siloscope wrote (changed by hand?)"
    return ""
