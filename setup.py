"""pip's build step (pyproject.toml): CMake builds the siloscope binary and the module _siloscope from this clone
with Debian's packages (what .ci/bootstrap installs), in build-pip/; the package gets the module beside its
Python files and the binary, with what it reads beside it (figure scripts, scenes), under siloscope/bin."""
import glob
import os
import re
import sys
import shutil
import subprocess

from setuptools import Distribution, setup
from setuptools.command.build_py import build_py

ROOT = os.path.dirname(os.path.abspath(__file__))


def cmake_version():
    """The version CMakeLists.txt defines (the one place it is written)."""
    with open(os.path.join(ROOT, "CMakeLists.txt")) as f:
        return re.search(r"project\(siloscope VERSION ([0-9.]+)", f.read()).group(1)


def need(tool, package):
    if not shutil.which(tool):
        sys.exit(f"siloscope: building needs {tool} (Debian's {package}): bash .ci/bootstrap installs it, or "
                 f"apt-get install {package}")


class BuildWithCMake(build_py):
    def run(self):
        need("cmake", "cmake")
        need("c++", "build-essential")
        super().run()
        # SILOSCOPE_BUILD_DIR: an existing CMake build of this clone to take the two targets from (the tests use
        # the suite's own build); otherwise a build of its own.
        build = os.environ.get("SILOSCOPE_BUILD_DIR") or os.path.join(ROOT, "build-pip")
        if not os.environ.get("SILOSCOPE_BUILD_DIR"):
            # The module for the Python that runs pip (its headers must be there: python3-dev for Debian's).
            made = subprocess.run(["cmake", "-S", ROOT, "-B", build, "-DCMAKE_BUILD_TYPE=Release",
                                   "-DBUILD_TESTING=OFF", f"-DPython_EXECUTABLE={sys.executable}"])
            if made.returncode != 0:
                sys.exit(f"siloscope: CMake could not configure the build for {sys.executable} (Python "
                         f"{sys.version.split()[0]}); the module needs that Python's headers and Debian's -dev "
                         "packages (bash .ci/bootstrap installs them for /usr/bin/python3)")
        subprocess.run(["cmake", "--build", build, "-j", str(os.cpu_count() or 2), "--target", "siloscope",
                        "_siloscope"], check=True)
        package = os.path.join(self.build_lib, "siloscope")
        with open(os.path.join(package, "_version.py"), "w") as f:
            f.write(f'version = "{cmake_version()}"  # from CMakeLists.txt\n')
        for module in glob.glob(os.path.join(build, "share", "siloscope", "python", "siloscope", "_siloscope*.so")):
            shutil.copy2(module, package)
        # The binary finds its share directory beside itself (BINDIR/share/siloscope).
        bindir = os.path.join(package, "bin")
        os.makedirs(bindir, exist_ok=True)
        shutil.copy2(os.path.join(build, "siloscope"), bindir)
        # ... and its picture and video readers in BINDIR/lib/siloscope (vision/codecs.h).
        os.makedirs(os.path.join(bindir, "lib", "siloscope"), exist_ok=True)
        shutil.copy2(os.path.join(build, "lib", "siloscope", "siloscope_codecs.so"),
                     os.path.join(bindir, "lib", "siloscope"))
        share = os.path.join(bindir, "share", "siloscope")
        shutil.rmtree(share, ignore_errors=True)
        shutil.copytree(os.path.join(build, "share", "siloscope"), share,
                        ignore=shutil.ignore_patterns("*.so", "__pycache__"))


class BinaryDistribution(Distribution):
    """The wheel holds a compiled module and a binary: a platform wheel, not py3-none-any."""

    def has_ext_modules(self):
        return True


if sys.version_info < (3, 11):
    sys.exit(f"siloscope needs Python 3.11 or later (tomllib); this is {sys.version.split()[0]} ({sys.executable})")
try:
    import wheel  # noqa: F401  pip builds a wheel with it
except ImportError:
    # pip asks for the metadata first (dist_info), which setuptools makes through bdist_wheel too.
    if any(a.startswith(("bdist_wheel", "dist_info", "editable_wheel")) for a in sys.argv):
        sys.exit(f"siloscope: building a wheel needs the wheel package for {sys.executable} (Debian: "
                 "python3-wheel; another Python: pip install wheel, or use /usr/bin/python3 -m pip)")

setup(version=cmake_version(), distclass=BinaryDistribution, cmdclass={"build_py": BuildWithCMake},
      options={"build": {"build_base": os.path.join("build-pip", "setuptools")},
               "egg_info": {"egg_base": "build-pip"}})
