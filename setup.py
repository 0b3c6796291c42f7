"""setuptools driving CMake: builds the mocapsolve_python target (python/CMakeLists.txt)
and installs python/mocapsolve with the compiled mocapsolve/_core module.

  pip install --no-index --no-build-isolation .     (in a venv with --system-site-packages)

CMake finds Python through the interpreter running this build; CMAKE_ARGS (environment)
adds configure arguments (e.g. -DCMAKE_CXX_COMPILER_LAUNCHER=ccache), CMAKE_BUILD_PARALLEL_LEVEL
the jobs (default 2), MOCAPSOLVE_CMAKE_BUILD_DIR the CMake build folder (default build-pip/).
"""
import glob
import os
import shlex
import shutil
import subprocess
import sys

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

ROOT = os.path.dirname(os.path.abspath(__file__))


class CMakeExtension(Extension):
    def __init__(self, name):
        super().__init__(name, sources=[])


class CMakeBuild(build_ext):
    def build_extension(self, ext):
        # At the depth of build/, so that ccache (CCACHE_BASEDIR) shares the objects.
        build = os.environ.get("MOCAPSOLVE_CMAKE_BUILD_DIR", os.path.join(ROOT, "build-pip"))
        configure = ["cmake", "-S", ROOT, "-B", build, "-DCMAKE_BUILD_TYPE=Release",
                     "-DPython3_EXECUTABLE=" + sys.executable, "-DMOCAPSOLVE_PYTHON=ON",
                     "-DMOCAPSOLVE_BUILD_TESTS=OFF", "-DMOCAPSOLVE_BUILD_BENCHMARKS=OFF"]
        configure += shlex.split(os.environ.get("CMAKE_ARGS", ""))
        subprocess.check_call(configure)
        jobs = os.environ.get("CMAKE_BUILD_PARALLEL_LEVEL", "2")
        subprocess.check_call(["cmake", "--build", build, "--target", "mocapsolve_python", "-j", jobs])
        built = glob.glob(os.path.join(build, "python", "mocapsolve", "_core*.so"))
        if len(built) != 1:
            raise RuntimeError("mocapsolve: expected one _core*.so under %s, found %s" % (build, built))
        target = self.get_ext_fullpath(ext.name)
        os.makedirs(os.path.dirname(target), exist_ok=True)
        shutil.copyfile(built[0], target)


setup(
    packages=["mocapsolve"],
    package_dir={"mocapsolve": "python/mocapsolve"},
    package_data={"mocapsolve": ["*.pyi", "py.typed"]},
    ext_modules=[CMakeExtension("mocapsolve._core")],
    cmdclass={"build_ext": CMakeBuild},
    zip_safe=False,
)
