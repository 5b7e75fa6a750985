# SPDX-License-Identifier: MIT
"""Builds the package elan with the project's CMake: `pip install --no-build-isolation
tools/python` (offline, with the distribution's setuptools; needs cmake, a C++20 compiler and the
packages tools/setup.sh installs). The compiled module is the CMake target elan_python."""

import os
import pathlib
import shutil
import subprocess
import sys

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

ROOT = pathlib.Path(__file__).resolve().parents[2]


class CMakeExtension(Extension):
    def __init__(self, name):
        super().__init__(name, sources=[])


class CMakeBuild(build_ext):
    def build_extension(self, ext):
        build = pathlib.Path(self.build_temp).resolve() / "cmake"
        subprocess.check_call(
            [
                "cmake", "-S", str(ROOT), "-B", str(build),
                "-DCMAKE_BUILD_TYPE=Release",
                "-DELAN_BUILD_TESTS=OFF", "-DELAN_BUILD_BENCH=OFF", "-DELAN_BUILD_TOOLS=OFF",
                "-DELAN_BUILD_PYTHON=ON", f"-DPython3_EXECUTABLE={sys.executable}",
            ]
        )
        jobs = os.environ.get("CMAKE_BUILD_PARALLEL_LEVEL", str(os.cpu_count() or 1))
        subprocess.check_call(
            ["cmake", "--build", str(build), "--target", "elan_python", "-j", jobs]
        )
        built = next((build / "tools" / "python" / "elan").glob("_elan*.so"))
        target = pathlib.Path(self.get_ext_fullpath(ext.name))
        target.parent.mkdir(parents=True, exist_ok=True)
        shutil.copy2(built, target)


setup(
    name="elan",
    version="0.1.0",
    description="Deterministic rigid-body physics engine",
    license="MIT",
    packages=["elan"],
    package_data={"elan": ["*.pyi", "py.typed"]},
    ext_modules=[CMakeExtension("elan._elan")],
    cmdclass={"build_ext": CMakeBuild},
    python_requires=">=3.8",
    install_requires=["numpy"],
    zip_safe=False,
)
