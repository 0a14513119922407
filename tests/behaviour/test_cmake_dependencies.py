"""CMake stops at configure time naming the Debian package of a missing
dependency (each made invisible to CMake here; nothing is uninstalled)."""
import os
import shutil
import subprocess

import pytest
from conftest import ROOT

CASES = {
    "libnanoflann-dev": ["-DCMAKE_IGNORE_PATH=/usr/include"],
    "libeigen3-dev": ["-DCMAKE_IGNORE_PATH=/usr/share/eigen3/cmake"],
    "petsc-dev": [],  # with PKG_CONFIG_LIBDIR pointing nowhere
    "libgtest-dev": ["-DCMAKE_DISABLE_FIND_PACKAGE_GTest=ON"],
}


@pytest.mark.skipif(shutil.which("cmake") is None, reason="needs cmake")
@pytest.mark.parametrize("package", list(CASES))
def test_missing_dependency_names_its_package(package, tmp_path):
    env = dict(os.environ, PKG_CONFIG_LIBDIR=str(tmp_path / "nowhere")) if package == "petsc-dev" else None
    result = subprocess.run(["cmake", "-S", str(ROOT), "-B", str(tmp_path / "build"), *CASES[package]],
                            capture_output=True, text=True, timeout=300, env=env)
    assert result.returncode != 0
    message = " ".join(result.stderr.split())
    assert f"install the Debian package {package}" in message, result.stderr
