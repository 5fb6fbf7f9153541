"""`cmake --install BUILD --component python --prefix P` gives a working package in
P/RHABEL_PYTHON_INSTALL_DIR (default lib/python3.X/site-packages)."""

import os
import re
import shutil
import subprocess
import sys

import pytest

from conftest import BINARY_DIR


def test_installed_package_imports_and_solves(tmp_path):
    cache = BINARY_DIR / "CMakeCache.txt"
    if not cache.is_file() or shutil.which("cmake") is None:
        pytest.skip(f"no configured build tree at {BINARY_DIR}")
    match = re.search(r"^RHABEL_PYTHON_INSTALL_DIR:\w+=(.*)$", cache.read_text(), re.MULTILINE)
    assert match, "RHABEL_PYTHON_INSTALL_DIR is not in the cache: is RHABEL_BUILD_PYTHON on?"
    prefix = tmp_path / "prefix"
    subprocess.run(["cmake", "--install", str(BINARY_DIR), "--component", "python", "--prefix", str(prefix)],
                   check=True, capture_output=True)
    site = prefix / match.group(1)
    assert (site / "rhabel" / "__init__.py").is_file()
    env = dict(os.environ, PYTHONPATH=str(site))
    code = ("import rhabel, sys; "
            "r = rhabel.solve({'material': {'alpha': 0.2, 'E1': 1, 'nu': 0.5, 'coulomb': 0}, 'speed': 1, "
            "'indentors': [{'shape': 'flat', 'width': 1, 'load': 1}]}); "
            "print(rhabel.__file__); print(r.indentors[0].contact_length)")
    run = subprocess.run([sys.executable, "-c", code], check=True, capture_output=True, text=True, env=env,
                         cwd=tmp_path)
    location, length = run.stdout.split()
    assert location.startswith(str(site)) and float(length) == 1.0
