#!/usr/bin/env bash
# CLI test of `rhabel rule gauss-jacobi N A B`:
#   bash test_rule.sh <path-to-rhabel-binary> <source-dir>
# Checks the CSV header, strictly increasing nodes, 17 significant digits, closed-form values
# (Chebyshev n = 3: x = cos(k pi/6), w = pi/3; Legendre n = 2: x = +-1/sqrt(3), w = 1), the
# complements 1 - x, 1 + x, and exit code 2 with a one-line message naming the bad argument.
set -u
rhabel="$1"
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }

# --- a good rule -------------------------------------------------------------------------
out="$("$rhabel" rule gauss-jacobi 3 -0.5 -0.5)"; rc=$?
[ "$rc" -eq 0 ] || fail "exit code $rc for a valid rule"
header="$(printf '%s\n' "$out" | head -n 1)"
[ "$header" = "x,one_minus_x,one_plus_x,weight" ] || fail "header is '$header'"
[ "$(printf '%s\n' "$out" | wc -l)" -eq 4 ] || fail "expected 1 header + 3 node lines"
# Chebyshev first kind: nodes -sqrt(3)/2, 0, sqrt(3)/2 in increasing order, weights pi/3.
printf '%s\n' "$out" | tail -n +2 | awk -F, '
  function abs(v) { return v < 0 ? -v : v }
  BEGIN { pi = atan2(0, -1); s = sqrt(3) / 2; expect[1] = -s; expect[2] = 0; expect[3] = s; bad = 0 }
  {
    if (NR > 1 && !($1 > prev)) { print "nodes not increasing at line " NR; bad = 1 }
    prev = $1
    if (abs($1 - expect[NR]) > 4e-16) { print "x[" NR "] = " $1; bad = 1 }
    if (abs($2 - (1 - expect[NR])) > 4e-16 || abs($3 - (1 + expect[NR])) > 4e-16) { print "complements wrong at line " NR; bad = 1 }
    if (abs($4 / (pi / 3) - 1) > 4e-16) { print "w[" NR "] = " $4; bad = 1 }
  }
  END { exit bad }' || fail "Chebyshev n = 3 values"
# 17 significant digits: pi/3 = 1.0471975511965976 needs all 17 to round-trip.
printf '%s\n' "$out" | tail -n 1 | grep -q ',1\.0471975511965976$' || fail "weight not printed with 17 digits"

# Legendre n = 2 (generic path): x = +-0.57735026918962573, w = 1.
out="$("$rhabel" rule gauss-jacobi 2 0 0)" || fail "Legendre n = 2 exit code"
printf '%s\n' "$out" | tail -n +2 | awk -F, '
  function abs(v) { return v < 0 ? -v : v }
  { x[NR] = $1; w[NR] = $4 }
  END { r = 1 / sqrt(3); exit !(abs(x[1] + r) < 4e-16 && abs(x[2] - r) < 4e-16 && abs(w[1] - 1) < 4e-16 && abs(w[2] - 1) < 4e-16) }' ||
  fail "Legendre n = 2 values"

# The complement near +1 keeps full relative accuracy where x does not (n = 65536, A = -0.9).
last="$("$rhabel" rule gauss-jacobi 65536 -0.9 0 | tail -n 1)"
awk -F, -v line="$last" 'BEGIN { split(line, f, ","); exit !(f[2] > 4.8857672333e-11 && f[2] < 4.8857672334e-11 &&
  f[4] > 1.22302724334 && f[4] < 1.22302724335) }' || fail "n = 65536 last node/weight: $last"

# --- bad input: exit code 2, one line naming the argument ----------------------------------
check_bad() {
  local name="$1"; shift
  local err rc
  err="$("$rhabel" "$@" 2>&1 >/dev/null)"; rc=$?
  [ "$rc" -eq 2 ] || fail "'$*' exit code $rc (expected 2)"
  [ "$(printf '%s\n' "$err" | wc -l)" -eq 1 ] || fail "'$*' message is not one line: $err"
  printf '%s\n' "$err" | grep -q "$name = " || fail "'$*' message does not name $name: $err"
}
check_bad N rule gauss-jacobi 0 0 0
check_bad N rule gauss-jacobi abc 0 0
check_bad N rule gauss-jacobi 2.5 0 0
check_bad N rule gauss-jacobi 100000001 0 0
check_bad A rule gauss-jacobi 3 -1 0
check_bad A rule gauss-jacobi 3 x 0
check_bad B rule gauss-jacobi 3 0 nan
check_bad B rule gauss-jacobi 3 0 -2
check_bad B rule gauss-jacobi 3 0 inf

# an unknown command is named, exit code 2
err="$("$rhabel" frobnicate 2>&1 >/dev/null)"; rc=$?
[ "$rc" -eq 2 ] || fail "'frobnicate' exit code $rc (expected 2)"
printf '%s\n' "$err" | grep -q "unknown command 'frobnicate'" || fail "'frobnicate' message: $err"

if [ "$failures" -ne 0 ]; then
  echo "$failures check(s) failed"
  exit 1
fi
echo "all rule checks passed"
