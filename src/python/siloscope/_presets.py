"""The preset scenes by name (`paper`, `paper-vibrated`, `pentagons`, ...), wherever the package is: in a clone
(assets/scenes), staged beside a build or installed (SHARE/scenes), or inside a pip-installed package
(siloscope/bin/share/siloscope/scenes). The binary finds the same files by the same names."""
import os

from ._errors import SiloscopeError

_HERE = os.path.dirname(os.path.abspath(__file__))


def _scene_dirs():
    return [os.path.normpath(p) for p in (
        os.path.join(_HERE, "..", "..", "..", "assets", "scenes"),     # a clone: src/python/siloscope
        os.path.join(_HERE, "..", "..", "scenes"),                     # SHARE/python/siloscope -> SHARE/scenes
        os.path.join(_HERE, "bin", "share", "siloscope", "scenes"))   # pip: siloscope/bin/share/siloscope
        if os.path.isdir(p)]


def presets():
    """The preset scenes' names, sorted (each is a scene file: `siloscope.scene_file(name)`)."""
    names = set()
    for d in _scene_dirs():
        names.update(f[:-5] for f in os.listdir(d) if f.endswith(".toml"))
    return sorted(names)


def scene_file(scene):
    """A scene given as a file or as a preset's name: the file's path (a name is looked up among the presets).
    Raises FileNotFoundError naming the presets when it is neither."""
    scene = os.fspath(scene)
    if os.path.exists(scene) or "/" in scene or scene.endswith(".toml"):
        return scene
    for d in _scene_dirs():
        p = os.path.join(d, scene + ".toml")
        if os.path.isfile(p):
            return p
    raise SceneNotFound(f"{scene}: no such scene file, and no preset scene of that name (presets: "
                        f"{', '.join(presets())})")


class SceneNotFound(SiloscopeError, FileNotFoundError):
    """A scene that is neither a file nor a preset's name."""
