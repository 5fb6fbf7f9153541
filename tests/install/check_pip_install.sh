#!/usr/bin/env bash
# CTest python.pip_install (label pip): `pip install .` of a copy of the source tree into a fresh
# venv, offline, as the README says:
#     python3 -m venv --system-site-packages V && V/bin/pip install --no-build-isolation --no-index .
# then, from another directory, imports rhabel from the venv, checks the metadata (version equal to
# rhabel.__version__), the files (with the type stubs), that the extension was built for the venv's
# interpreter, and solves a scene.
#   bash check_pip_install.sh SOURCE_DIR BINARY_DIR PYTHON
# Everything lives in BINARY_DIR/pip-install-check/ at fixed paths (the copy, the venv, the CMake
# tree of setup.py), so that a second run recompiles only what changed: the first run builds the
# library and the extension (minutes on two cores), hence a label of its own (ctest -L pip).
set -euo pipefail
src=$1; bin=$2; python=$3
work=$bin/pip-install-check
for module in venv ensurepip setuptools wheel; do
  if ! "$python" -c "import $module" 2> /dev/null; then
    echo "SKIP: $python has no module $module (Debian: python3-venv, python3-setuptools, python3-wheel)"
    exit 77
  fi
done
rm -rf "$work/src" "$work/venv" "$work/run"
mkdir -p "$work/src" "$work/run"

# The files of a clone: no build trees, no git metadata, no egg-info left by an in-tree install.
tar -C "$src" --exclude='./build*' --exclude='./.git' --exclude='./out' --exclude='*.egg-info' \
    --exclude='__pycache__' -cf - . | tar -C "$work/src" -xf -

"$python" -m venv --system-site-packages "$work/venv"
if ! RHABEL_CMAKE_BUILD_DIR="$work/cmake" "$work/venv/bin/pip" install --no-build-isolation --no-index \
       "$work/src" > "$work/pip.log" 2>&1; then
  tail -40 "$work/pip.log"
  echo "FAIL: pip install (log: $work/pip.log)"
  exit 1
fi

cd "$work/run"
"$work/venv/bin/python" - "$work" <<'PY'
import importlib.metadata
import pathlib
import sys

import rhabel

work = pathlib.Path(sys.argv[1])
venv = (work / "venv").resolve()
where = pathlib.Path(rhabel.__file__).resolve()
assert venv in where.parents, f"rhabel imported from {where}, not from the venv {venv}"
assert importlib.metadata.version("rhabel") == rhabel.__version__, (importlib.metadata.version("rhabel"),
                                                                    rhabel.__version__)
meta = importlib.metadata.metadata("rhabel")
assert meta["Name"] == "rhabel" and "numpy" in " ".join(meta.get_all("Requires-Dist")), dict(meta)
files = {str(f) for f in importlib.metadata.files("rhabel")}
for name in ("rhabel/__init__.py", "rhabel/abel.py", "rhabel/py.typed", "rhabel/__init__.pyi", "rhabel/abel.pyi"):
    assert name in files, f"{name} is not installed: {sorted(files)}"
# The extension was built for the interpreter that ran pip (CMake's Python3_EXECUTABLE).
cache = (work / "cmake" / "CMakeCache.txt").read_text()
interpreter = [line.split("=", 1)[1] for line in cache.splitlines() if line.startswith("Python3_EXECUTABLE:")]
assert len(interpreter) == 1 and pathlib.Path(interpreter[0]).parent == work / "venv" / "bin", interpreter
r = rhabel.solve({"material": {"alpha": 0.3, "E1": 1.0e6, "nu": 0.5, "coulomb": 0.0}, "speed": 0.01,
                  "indentors": [{"shape": "parabolic", "radius": 0.02, "load": 100.0}]}, grid=11)
assert r.diagnostics.status == "ok" and r.indentors[0].pressure.p.size == 11, r
assert repr(r).startswith("rhabel.Result: 1 contact, status ok") and type(r.to_dict()) is dict, repr(r)
print(f"pip install: rhabel {rhabel.__version__} from {where.parent}, C_f = {r.indentors[0].hysteretic_friction:.6g}")
PY
