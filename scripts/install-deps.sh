#!/usr/bin/env bash
# Installs the Debian packages rhabel needs, and only those that are missing.
# Idempotent: a second run does nothing and touches no package index.
# Usage: scripts/install-deps.sh [--mpi]
set -euo pipefail

packages=(
  g++ cmake make            # toolchain
  libboost-dev              # Boost.Math, Boost.Multiprecision (header-only)
  libeigen3-dev             # Golub-Welsch eigenproblems, dense linear algebra
  libgsl-dev                # comparison baselines in studies and benchmarks
  libfftw3-dev              # FFTW: the boundary-element products of a sampled profile (punch)
  doctest-dev               # unit tests
  nlohmann-json3-dev        # scene and result JSON in the command line
  libcli11-dev              # command-line parsing
  libbenchmark-dev          # Google Benchmark for bench/
  python3 python3-matplotlib  # the main job's plot
  pybind11-dev python3-dev    # the Python package rhabel (python/)
  python3-numpy python3-pytest  # its arrays and its tests (tests/python/)
  python3-setuptools python3-wheel python3-pip python3-venv  # `pip install .` offline (pyproject.toml, setup.py)
  python3-mypy                  # checks the package's type stubs (tests/python/test_result_view.py)
  python3-hypothesis            # property-based tests of the Python API (tests/python/test_properties.py)
  python3-nbclient python3-nbformat python3-nbconvert python3-ipykernel  # notebooks/, run by CTest (label notebooks)
  clang-14 libclang-rt-14-dev  # libFuzzer and its sanitizers: make test-fuzz (tests/fuzz/)
)

# `make test` (scripts/install-deps.sh --mpi) also tests `rhabel sweep` under mpirun; the main
# job (`make demo`) needs no MPI.
if [ "${1:-}" = "--mpi" ]; then
  packages+=(libopenmpi-dev openmpi-bin)  # Debian's OpenMPI: RHABEL_WITH_MPI, cli.mpi_sweep
fi

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done
[ ${#missing[@]} -eq 0 ] && exit 0

echo "rhabel: installing missing Debian packages: ${missing[*]}" >&2
sudo_cmd=()
[ "$(id -u)" -ne 0 ] && sudo_cmd=(sudo)
export DEBIAN_FRONTEND=noninteractive
"${sudo_cmd[@]}" apt-get update -qq
"${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
