"""pip's build step (pyproject.toml): CMake builds the siloscope binary and the module _siloscope from this clone
with Debian's packages (what .ci/bootstrap installs), in build-pip/; the package gets the module beside its
Python files and the binary, with what it reads beside it (figure scripts, scenes), under siloscope/bin."""
import glob
import os
import shutil
import subprocess

from setuptools import setup
from setuptools.command.build_py import build_py

ROOT = os.path.dirname(os.path.abspath(__file__))


class BuildWithCMake(build_py):
    def run(self):
        super().run()
        # SILOSCOPE_BUILD_DIR: an existing CMake build of this clone to take the two targets from (the tests use
        # the suite's own build); otherwise a build of its own.
        build = os.environ.get("SILOSCOPE_BUILD_DIR") or os.path.join(ROOT, "build-pip")
        if not os.environ.get("SILOSCOPE_BUILD_DIR"):
            subprocess.run(["cmake", "-S", ROOT, "-B", build, "-DCMAKE_BUILD_TYPE=Release",
                            "-DBUILD_TESTING=OFF"], check=True)
        subprocess.run(["cmake", "--build", build, "-j", str(os.cpu_count() or 2), "--target", "siloscope",
                        "_siloscope"], check=True)
        package = os.path.join(self.build_lib, "siloscope")
        for module in glob.glob(os.path.join(build, "share", "siloscope", "python", "siloscope", "_siloscope*.so")):
            shutil.copy2(module, package)
        # The binary finds its share directory beside itself (BINDIR/share/siloscope).
        bindir = os.path.join(package, "bin")
        os.makedirs(bindir, exist_ok=True)
        shutil.copy2(os.path.join(build, "siloscope"), bindir)
        share = os.path.join(bindir, "share", "siloscope")
        shutil.rmtree(share, ignore_errors=True)
        shutil.copytree(os.path.join(build, "share", "siloscope"), share,
                        ignore=shutil.ignore_patterns("*.so", "__pycache__"))


setup(cmdclass={"build_py": BuildWithCMake},
      options={"build": {"build_base": os.path.join("build-pip", "setuptools")},
               "egg_info": {"egg_base": "build-pip"}})
