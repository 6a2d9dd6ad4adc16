"""`pip install .`: builds the _throng module with the project's CMake (the library targets and the
module only: no tests, benches or fuzz targets) and packages it with python/throng/ (docs/python.md).

By default it configures and builds build-python/ (static libraries: a self-contained module). With
THRONG_CMAKE_BUILD_DIR naming an already configured build directory (the README's build/, say) it
builds the module there instead and packages that one: quick when the build is current, as in the
pip_install test; such a module links that build's libraries (shared in a default build), so the
installation works for as long as that directory exists — for development and CI, not for wheels
to hand out."""
import atexit
import os
import shutil
import subprocess
import sys
import tempfile

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

ROOT = os.path.dirname(os.path.abspath(__file__))
BUILD_DIR_VARIABLE = "THRONG_CMAKE_BUILD_DIR"


def cmake_build_dir():
    """The CMake build directory to build the module in: THRONG_CMAKE_BUILD_DIR's, configured, or
    build-python/, configured here when it is not yet."""
    given = os.environ.get(BUILD_DIR_VARIABLE)
    if given:
        build = os.path.abspath(given)
        if not os.path.exists(os.path.join(build, "CMakeCache.txt")):
            sys.exit(f"throng: {BUILD_DIR_VARIABLE}={given} is not a configured CMake build directory (no CMakeCache.txt); "
                     f"configure it first (README) or unset {BUILD_DIR_VARIABLE} to build in build-python/")
        return build
    build = os.path.join(ROOT, "build-python")
    if not os.path.exists(os.path.join(build, "CMakeCache.txt")):
        # Static libraries: the wheel's module is self-contained (no libthrong_*.so to find).
        subprocess.check_call(["cmake", "-S", ROOT, "-B", build, "-DCMAKE_BUILD_TYPE=Release",
                               f"-DPython3_EXECUTABLE={sys.executable}", "-DTHRONG_BUILD_TESTS=OFF",
                               "-DBUILD_SHARED_LIBS=OFF", "-DTHRONG_BUILD_BENCHES=OFF", "-DTHRONG_BUILD_FUZZ=OFF"])
    return build


class CMakeBuild(build_ext):
    def build_extension(self, ext):
        build = cmake_build_dir()
        subprocess.check_call(["cmake", "--build", build, "--target", "throng_python", "-j", str(os.cpu_count() or 2)])
        built = os.path.join(build, "python", "throng")
        target = os.path.dirname(self.get_ext_fullpath(ext.name))
        os.makedirs(target, exist_ok=True)
        for name in os.listdir(built):
            if os.path.isfile(os.path.join(built, name)):  # not __pycache__
                shutil.copy2(os.path.join(built, name), os.path.join(target, name))


# setuptools' own scratch space (build/, throng.egg-info/): a fresh directory per run, removed at exit,
# so nothing stale from an earlier run reaches a wheel and nothing is written to the checkout.
SCRATCH = tempfile.mkdtemp(prefix="throng-setuptools-")
atexit.register(shutil.rmtree, SCRATCH, True)
setup(options={"build": {"build_base": SCRATCH}, "egg_info": {"egg_base": SCRATCH}},
      packages=["throng"], package_dir={"throng": "python/throng"},
      package_data={"throng": ["*.pyi", "py.typed"]},
      ext_modules=[Extension("throng._throng", sources=[])], cmdclass={"build_ext": CMakeBuild})
