"""Builds Tessera's extension module tessera._tessera with CMake (python/CMakeLists.txt) and packages it.

Offline, from Debian packages alone: `pip install --no-build-isolation ./python` in a virtual environment made with
--system-site-packages (docs/python.md). The module is built in build/python at the repository root (a release build
of the library and the module only), or in the configured build folder TESSERA_BUILD_DIR names (absolute, or relative to the repository root; make test points it at
build/release, which has already built it).
"""
import os
import shutil
import subprocess
import sys
import sysconfig
from pathlib import Path

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

ROOT = Path(__file__).resolve().parent.parent


class CMakeExtension(Extension):
    """An extension CMake builds: no sources for setuptools to compile."""

    def __init__(self, name):
        super().__init__(name, sources=[])


class CMakeBuild(build_ext):
    def build_extension(self, ext):
        given = os.environ.get("TESSERA_BUILD_DIR")
        build_dir = (ROOT / given).resolve() if given else ROOT / "build" / "python"  # relative: to the root
        if not given:
            # This interpreter's headers and numpy; the library in release mode, without tests and examples.
            subprocess.check_call(["cmake", "-S", str(ROOT), "-B", str(build_dir), "-G", "Ninja",
                                   "-DCMAKE_BUILD_TYPE=Release", "-DTESSERA_BUILD_PYTHON=ON",
                                   "-DTESSERA_BUILD_TESTS=OFF", "-DTESSERA_BUILD_EXAMPLES=OFF",
                                   f"-DPython_EXECUTABLE={sys.executable}"])
        elif not (build_dir / "CMakeCache.txt").exists():
            sys.exit(f"setup.py: TESSERA_BUILD_DIR={given} is not a configured CMake build folder")
        jobs = os.environ.get("CMAKE_BUILD_PARALLEL_LEVEL", str(os.cpu_count() or 1))
        subprocess.check_call(["cmake", "--build", str(build_dir), "--target", "_tessera", "-j", jobs])
        built = build_dir / "python" / "tessera" / ("_tessera" + sysconfig.get_config_var("EXT_SUFFIX"))
        if not built.exists():
            sys.exit(f"setup.py: {built} was not built: is {build_dir} configured for this Python "
                     f"({sys.version.split()[0]}, -DPython_EXECUTABLE)?")
        target = Path(self.get_ext_fullpath(ext.name))
        target.parent.mkdir(parents=True, exist_ok=True)
        shutil.copyfile(built, target)


setup(ext_modules=[CMakeExtension("tessera._tessera")], cmdclass={"build_ext": CMakeBuild})
