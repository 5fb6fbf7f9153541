#!/usr/bin/env bash
# README example (command line): solve the scene file; the result is JSON on stdout.
# Run from the source directory after `make demo` or `make test`: bash examples/snippets/cli.sh
set -euo pipefail
rhabel=${RHABEL:-build/bin/rhabel}
"$rhabel" solve examples/snippets/scene.json
