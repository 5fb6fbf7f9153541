#!/usr/bin/env bash
# Installs the already-built tree into a scratch prefix and builds a small consumer
# project against it with find_package(rhabel): the installed package must be usable.
set -euo pipefail
src=$1; bin=$2
scratch=$bin/install-check
rm -rf "$scratch"
cmake --install "$bin" --prefix "$scratch/prefix" >/dev/null
cmake -S "$src/tests/install/consumer" -B "$scratch/build" -DCMAKE_PREFIX_PATH="$scratch/prefix" \
      -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$scratch/build" >/dev/null
"$scratch/build/consumer"
