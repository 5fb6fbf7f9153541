"""The build step of `pip install .` (metadata: pyproject.toml).

build_ext configures the C++ project with CMake (only what the extension needs: no tests, command
line, studies or benchmarks), builds the target rhabel_python with the interpreter running this
script (sys.executable: the venv's when pip runs in a venv) and copies the extension rhabel._rhabel
into the wheel; the package's .py and .pyi files come from python/rhabel/.

The CMake tree is build-pip/temp.*/cmake, kept between runs so that a second install recompiles only
what changed; RHABEL_CMAKE_BUILD_DIR names another one. Parallel jobs: `pip install` passes none,
so CMAKE_BUILD_PARALLEL_LEVEL if set, else every core.
"""

import os
import pathlib
import re
import shutil
import subprocess
import sys
import sysconfig

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

ROOT = pathlib.Path(__file__).resolve().parent


def project_version():
    """The version of project(rhabel VERSION x.y.z) in CMakeLists.txt: the one place it is written."""
    match = re.search(r"project\(\s*rhabel\s+VERSION\s+([0-9]+(?:\.[0-9]+)*)", (ROOT / "CMakeLists.txt").read_text())
    if match is None:
        raise RuntimeError("setup.py: no project(rhabel VERSION ...) in CMakeLists.txt")
    return match.group(1)


class CMakeBuild(build_ext):
    """Builds rhabel._rhabel with CMake instead of compiling sources itself."""

    def build_extension(self, ext):
        cmake_dir = pathlib.Path(os.environ.get("RHABEL_CMAKE_BUILD_DIR") or pathlib.Path(self.build_temp) / "cmake")
        cmake_dir = cmake_dir.resolve()
        configure = ["cmake", "-S", str(ROOT), "-B", str(cmake_dir),
                     "-DCMAKE_BUILD_TYPE=Release",
                     f"-DPython3_EXECUTABLE={sys.executable}",
                     "-DRHABEL_REQUIRE_PYTHON=ON",
                     "-DRHABEL_BUILD_TESTS=OFF", "-DRHABEL_BUILD_CLI=OFF",
                     "-DRHABEL_BUILD_STUDIES=OFF", "-DRHABEL_BUILD_BENCHMARKS=OFF"]
        jobs = self.parallel or os.environ.get("CMAKE_BUILD_PARALLEL_LEVEL") or os.cpu_count() or 1
        subprocess.run(configure, check=True)
        subprocess.run(["cmake", "--build", str(cmake_dir), "--target", "rhabel_python", "-j", str(jobs)], check=True)
        built = cmake_dir / "python" / "rhabel" / ("_rhabel" + sysconfig.get_config_var("EXT_SUFFIX"))
        if not built.is_file():
            raise RuntimeError(f"setup.py: CMake did not build {built} (for the interpreter {sys.executable})")
        target = pathlib.Path(self.get_ext_fullpath(ext.name))
        target.parent.mkdir(parents=True, exist_ok=True)
        shutil.copyfile(built, target)


setup(version=project_version(),
      ext_modules=[Extension("rhabel._rhabel", sources=[])],
      cmdclass={"build_ext": CMakeBuild},
      # Not build/: that is the CMake preset's build tree.
      options={"build": {"build_base": "build-pip"}})
