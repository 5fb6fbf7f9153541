#!/usr/bin/env bash
# CTest driver of the README's examples (examples/snippets/, label `snippets`):
#   run_snippet.sh SOURCE_DIR cli RHABEL_CLI        the shell example: JSON whose status is ok and whose
#                                                   contacts and C_f agree with examples/snippets/solve.out
#   run_snippet.sh SOURCE_DIR python PYTHON          the Python example: output equal to solve.out
#   run_snippet.sh SOURCE_DIR cpp SNIPPET_BINARY     the C++ example: output equal to solve.out
# solve.out is the output the README shows (6 significant digits, so rounding-level changes of the
# solver do not touch it; a change that moves a printed digit fails here and the README must follow).
set -euo pipefail
src=$1 mode=$2 tool=$3
cd "$src"
expected=examples/snippets/solve.out
case "$mode" in
  cli)
    RHABEL="$tool" bash examples/snippets/cli.sh > "${TMPDIR:-/tmp}/rhabel_snippet_cli.$$.json"
    /usr/bin/python3 - "${TMPDIR:-/tmp}/rhabel_snippet_cli.$$.json" "$expected" <<'PY'
import json, sys
r = json.load(open(sys.argv[1]))
assert r["diagnostics"]["status"] == "ok", r["diagnostics"]
lines = [l for l in open(sys.argv[2]) if " contact [" in l]
assert len(lines) == len(r["indentors"]), lines
for ind, line in zip(r["indentors"], lines):
    a, b = ind["contact"]
    want = f"contact [{a:.6g}, {b:.6g}] m, C_f = {ind['hysteretic_friction']:.6g},"
    assert want in line, (want, line)
print("cli snippet: status ok, contacts and C_f as in solve.out")
PY
    rm -f "${TMPDIR:-/tmp}/rhabel_snippet_cli.$$.json"
    ;;
  python) diff -u "$expected" <("$tool" examples/snippets/solve.py) ;;
  cpp) diff -u "$expected" <("$tool") ;;
  *) echo "run_snippet.sh: unknown mode $mode" >&2; exit 2 ;;
esac
