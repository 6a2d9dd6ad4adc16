"""`pip install .`: builds the _throng module with the project's CMake (the library targets and the
module only: no tests, benches or fuzz targets) and packages it with python/throng/ (docs/python.md)."""
import os
import shutil
import subprocess
import sys

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

ROOT = os.path.dirname(os.path.abspath(__file__))


class CMakeBuild(build_ext):
    def build_extension(self, ext):
        build = os.path.join(ROOT, "build-python")
        if not os.path.exists(os.path.join(build, "CMakeCache.txt")):
            # Static libraries: the wheel's module is self-contained (no libthrong_*.so to find).
            subprocess.check_call(["cmake", "-S", ROOT, "-B", build, "-DCMAKE_BUILD_TYPE=Release",
                                   f"-DPython3_EXECUTABLE={sys.executable}", "-DTHRONG_BUILD_TESTS=OFF",
                                   "-DBUILD_SHARED_LIBS=OFF", "-DTHRONG_BUILD_BENCHES=OFF", "-DTHRONG_BUILD_FUZZ=OFF"])
        subprocess.check_call(["cmake", "--build", build, "--target", "throng_python", "-j", str(os.cpu_count() or 2)])
        built = os.path.join(build, "python", "throng")
        target = os.path.dirname(self.get_ext_fullpath(ext.name))
        os.makedirs(target, exist_ok=True)
        for name in os.listdir(built):
            shutil.copy2(os.path.join(built, name), os.path.join(target, name))


setup(packages=["throng"], package_dir={"throng": "python/throng"},
      package_data={"throng": ["*.pyi", "py.typed"]},
      ext_modules=[Extension("throng._throng", sources=[])], cmdclass={"build_ext": CMakeBuild})
