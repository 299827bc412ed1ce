"""The extension mpcal._mpcal, built by the project's CMake (python/),
for `pip install --no-build-isolation .` and `python3 -m build --no-isolation`.
The rest of the metadata is in pyproject.toml."""
import os
import pathlib
import re
import shutil
import subprocess
import sys

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

ROOT = pathlib.Path(__file__).resolve().parent


def project_version():
    """The version CMakeLists.txt's project() gives, the one place it is set."""
    text = (ROOT / "CMakeLists.txt").read_text()
    return re.search(r"project\(mpcal VERSION ([0-9.]+)", text).group(1)


class CMakeBuild(build_ext):
    def build_extension(self, ext):
        # MPCAL_BUILD_DIR: a tree CMake configured already (`make build`'s
        # build/), in which only the extension is brought up to date, instead
        # of a fresh tree that compiles the whole library again.
        given = os.environ.get("MPCAL_BUILD_DIR")
        tree = (pathlib.Path(given) if given else
                pathlib.Path(self.build_temp) / "cmake").resolve()
        if not given:
            subprocess.run(["cmake", "-S", str(ROOT), "-B", str(tree),
                            "-DCMAKE_BUILD_TYPE=Release", "-DMPCAL_BUILD_TESTS=OFF",
                            "-DMPCAL_BUILD_BENCH=OFF", "-DMPCAL_BUILD_EXAMPLES=OFF",
                            f"-DPython3_EXECUTABLE={sys.executable}"], check=True)
        jobs = os.environ.get("MPCAL_JOBS", str(os.cpu_count() or 1))
        subprocess.run(["cmake", "--build", str(tree), "--target", "_mpcal", "-j", jobs],
                       check=True)
        built = next((tree / "python" / "mpcal").glob("_mpcal*.so"))
        target = pathlib.Path(self.get_ext_fullpath(ext.name))
        target.parent.mkdir(parents=True, exist_ok=True)
        shutil.copy2(built, target)


setup(version=project_version(),
      ext_modules=[Extension("mpcal._mpcal", sources=[])],
      cmdclass={"build_ext": CMakeBuild})
