#!/usr/bin/env bash
# MPI test of `rhabel sweep` (registered as cli.mpi_sweep when built with RHABEL_WITH_MPI):
#   bash mpi_sweep.sh <path-to-rhabel-binary> <source-dir> <mpiexec>
# 2 ranks on loopback must write the same rows as the threaded single process (every column but
# `seconds`, compared as text, so bit for bit), also when resuming a file that already holds an
# unordered subset of the rows; bad input ends every rank cleanly with one line and exit code 2.
set -u
rhabel="$(cd "$(dirname "$1")" && pwd)/$(basename "$1")"; src="$2"; mpiexec="$3"
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }
py=/usr/bin/python3; [ -x "$py" ] || py=python3
tmp="$(mktemp -d)"; trap 'rm -rf "$tmp"' EXIT
mpi=("$mpiexec" --allow-run-as-root --oversubscribe -np 2)
# Loopback only (CI containers have no network; shared memory may be missing too).
export OMPI_MCA_btl=self,tcp OMPI_MCA_btl_tcp_if_include=lo OMPI_MCA_oob_tcp_if_include=lo
export OMPI_MCA_rmaps_base_oversubscribe=1

same_rows() {
  "$py" - "$1" "$2" <<'PY'
import csv, sys
def load(p):
    rows = list(csv.reader(open(p, newline="")))
    i = rows[0].index("seconds")
    return [r[:i] + r[i + 1:] for r in rows]
a, b = load(sys.argv[1]), load(sys.argv[2])
assert [int(r[0]) for r in a[1:]] == list(range(len(a) - 1)), "rows not in order"
assert a == b, "files differ"
PY
}

cat > "$tmp/sweep.json" <<'JSON'
{"scene": {"material": {"alpha": 0.3, "E1": 1.0e6, "nu": 0.3, "coulomb": 0.5}, "speed": 0.01,
           "indentors": [{"shape": "parabolic", "radius": 0.02, "load": 100.0},
                         {"shape": "wedge", "slope_leading": 0.05, "slope_trailing": 0.05, "load": 50.0, "apex": 0.05}]},
 "axes": [{"path": "speed", "log_range": {"from": 1e-4, "to": 10, "count": 6}},
          {"path": "material.alpha", "values": [0.0, 0.2, 0.55, 1.5]},
          {"path": "indentors[0].load", "values": [30, 100, 300]}]}
JSON
"$rhabel" sweep "$tmp/sweep.json" --out "$tmp/threads.csv" 2> "$tmp/err"; rc_threads=$?
"${mpi[@]}" "$rhabel" sweep "$tmp/sweep.json" --out "$tmp/mpi.csv" > "$tmp/out" 2> "$tmp/err"; rc=$?
[ "$rc" -eq "$rc_threads" ] || fail "exit codes: mpirun $rc, threads $rc_threads ($(head -3 "$tmp/err"))"
[ -s "$tmp/out" ] && fail "mpirun: something on stdout: $(head -3 "$tmp/out")"
same_rows "$tmp/mpi.csv" "$tmp/threads.csv" || fail "2 MPI ranks differ from the threaded run"
grep -q ",invalid_scene," "$tmp/mpi.csv" || fail "expected invalid rows (alpha = 1.5)"

# Resume under MPI from a file holding every third row in reverse order.
"$py" - "$tmp/threads.csv" "$tmp/partial.csv" <<'PY'
import sys
lines = open(sys.argv[1]).read().splitlines(keepends=True)
with open(sys.argv[2], "w") as f:
    f.write(lines[0] + "".join(reversed(lines[1::3])))
PY
"${mpi[@]}" "$rhabel" sweep "$tmp/sweep.json" --out "$tmp/partial.csv" > /dev/null 2> "$tmp/err"
same_rows "$tmp/partial.csv" "$tmp/threads.csv" || fail "MPI resume differs from the threaded run"

# A master-curve sweep, JSON lines.
cat > "$tmp/rubber.json" <<JSON
{"scene": {"material": {"master_curve": "$src/examples/materials/filled_rubber.csv", "nu": 0.5, "coulomb": 0.3},
           "speed": 0.01, "indentors": [{"shape": "parabolic", "radius": 0.01, "load": 500}]},
 "axes": [{"path": "speed", "log_range": {"from": 1e-5, "to": 10, "count": 13}}]}
JSON
"$rhabel" sweep "$tmp/rubber.json" --jsonl --out "$tmp/r_threads.jsonl" 2> /dev/null
"${mpi[@]}" "$rhabel" sweep "$tmp/rubber.json" --jsonl --out "$tmp/r_mpi.jsonl" > /dev/null 2> "$tmp/err" \
  || fail "master-curve sweep under mpirun: $(head -3 "$tmp/err")"
diff <(sed 's/"seconds":[^,]*,//' "$tmp/r_threads.jsonl") <(sed 's/"seconds":[^,]*,//' "$tmp/r_mpi.jsonl") > /dev/null \
  || fail "master-curve sweep: MPI differs from threads"
[ "$(wc -l < "$tmp/r_mpi.jsonl")" -eq 13 ] || fail "master-curve sweep: expected 13 rows"

# Bad input and rows not ok (issue 31): every rank ends with MPI_Finalize and the same code, rank 0
# alone prints one line, and no MPI_ABORT banner; with mpirun -q nothing else is printed at all.
cat > "$tmp/bad_axis.json" <<'JSON'
{"scene": {"material": {"alpha": 0.3, "E1": 1e6, "nu": 0.3, "coulomb": 0}, "speed": 1,
           "indentors": [{"shape": "flat", "width": 0.01, "load": 1}]},
 "axes": [{"path": "sped", "values": [1, 2]}]}
JSON
"${mpi[@]}" "$rhabel" sweep "$tmp/bad_axis.json" --out "$tmp/bad.csv" > /dev/null 2> "$tmp/err"; rc=$?
[ "$rc" -eq 2 ] || fail "bad axis under mpirun: exit $rc, expected 2"
[ "$(grep -c '^rhabel: ' "$tmp/err")" -eq 1 ] && grep -q '^rhabel: sweep: axes\[0\].path = "sped"' "$tmp/err" \
  || fail "bad axis under mpirun: not one rhabel line: $(cat "$tmp/err")"
grep -q "MPI_ABORT" "$tmp/err" && fail "bad axis under mpirun: MPI_ABORT banner"
[ -e "$tmp/bad.csv" ] && fail "bad axis under mpirun: an output file was created"
"${mpi[@]}" -q "$rhabel" sweep "$tmp/bad_axis.json" --out "$tmp/bad.csv" > /dev/null 2> "$tmp/err"; rc=$?
[ "$rc" -eq 2 ] && [ "$(wc -l < "$tmp/err")" -eq 1 ] || fail "bad axis under mpirun -q: exit $rc, $(cat "$tmp/err")"
echo "junk" > "$tmp/foreign.jsonl"
"${mpi[@]}" -q "$rhabel" sweep "$tmp/rubber.json" --jsonl --out "$tmp/foreign.jsonl" > /dev/null 2> "$tmp/err"; rc=$?
[ "$rc" -eq 2 ] && [ "$(wc -l < "$tmp/err")" -eq 1 ] && grep -q "foreign.jsonl line 1" "$tmp/err" \
  || fail "foreign output under mpirun -q: exit $rc, $(cat "$tmp/err")"
"${mpi[@]}" -q "$rhabel" sweep "$tmp/sweep.json" --out "$tmp/not_ok.csv" > /dev/null 2> "$tmp/err"; rc=$?
[ "$rc" -eq 3 ] && [ ! -s "$tmp/err" ] || fail "rows not ok under mpirun -q: exit $rc (expected 3), $(cat "$tmp/err")"

[ "$failures" -eq 0 ] && echo "mpi_sweep: all checks passed"
exit $(( failures > 0 ))
