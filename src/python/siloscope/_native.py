"""The compiled module (_siloscope, pybind11) when it is there: the simulation in process, and the binary's
own readers' checks, so that a run's files are checked by one reader whichever language reads them."""
import functools
import glob
import importlib.util
import os


@functools.lru_cache(maxsize=1)
def module_or_none():
    """The module beside this package (a build's staged copy, a pip install), else the one installed with it
    (PREFIX/lib/siloscope for PREFIX/share/siloscope/python/siloscope), else the one a build of this clone
    staged; None without one."""
    try:
        from . import _siloscope
        return _siloscope
    except ImportError:
        pass
    here = os.path.dirname(os.path.abspath(__file__))
    found = []
    for where in (os.path.join(here, "..", "..", "..", "..", "lib", "siloscope"),
                  os.path.join(here, "..", "..", "..", "build", "share", "siloscope", "python", "siloscope")):
        found = found or sorted(glob.glob(os.path.join(where, "_siloscope*.so")))
    if not found:
        return None
    spec = importlib.util.spec_from_file_location("siloscope._siloscope", found[0])
    module = importlib.util.module_from_spec(spec)
    try:
        spec.loader.exec_module(module)
    except ImportError:  # built for another Python
        return None
    return module


def checked(call, *args):
    """The module's reader check `call` on `args`, its refusal as a SiloscopeError with its message; nothing
    without the module."""
    from ._errors import SiloscopeError
    m = module_or_none()
    if m is None:
        return None
    try:
        return getattr(m, call)(*args)
    except ValueError as e:
        raise SiloscopeError(str(e)) from None
