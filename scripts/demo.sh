#!/usr/bin/env bash
# The main job: placeholder until the punch layer lands.
set -euo pipefail
cd "$(dirname "$0")/.."
./build/bin/rhabel rule gauss-jacobi 8 -0.5 0
