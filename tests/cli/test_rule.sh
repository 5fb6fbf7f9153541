#!/usr/bin/env bash
# CLI test of `rhabel rule gauss-jacobi N A B`:
#   bash test_rule.sh <path-to-rhabel-binary> <source-dir>
# Checks the CSV header, strictly increasing nodes, 17 significant digits, closed-form values
# (Chebyshev n = 3: x = cos(k pi/6), w = pi/3; Legendre n = 2: x = +-1/sqrt(3), w = 1), the
# complements 1 - x, 1 + x, and exit code 2 with a one-line message naming the bad argument;
# issue 14: exponents beyond (-1, 30] refused, subnormal ones accepted, the corners of the range
# give finite positive weights with the right sum, a failed write to stdout is exit code 2 with
# one line, arguments holding newlines give one-line messages, the exit codes are in --help.
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

# --- issue 14: exponents beyond the accuracy contract (-1, 30] are refused, never 0/inf/NaN -----
# Each of these exited 0 with weights 0 (the sum is 2^2001 B(1001, 1001) = 0.056), NaN or inf,
# or exited 1 as an internal error, or took 75 s.
check_bad A rule gauss-jacobi 2 1000 1000
check_bad A rule gauss-jacobi 1 1e6 0
check_bad B rule gauss-jacobi 2 -0.999999999999 1e3
check_bad A rule gauss-jacobi 10 1e300 0
check_bad A rule gauss-jacobi 10000 300 -0.9
check_bad B rule gauss-jacobi 3 0 30.000000000000004
check_bad A rule gauss-jacobi 3 1e400 0
err="$("$rhabel" rule gauss-jacobi 2 1000 1000 2>&1 >/dev/null)"
printf '%s\n' "$err" | grep -q -F "(-1, 30]" || fail "the limit 30 is not named: $err"
# Inside the range, at its corners (30, -1 + 2^-53 ~ -0.9999999999999999, a subnormal) on both
# paths: exit 0, every weight finite and positive, and the sum of the weights equal to the mass
# 2^(A+B+1) Gamma(A+1) Gamma(B+1) / Gamma(A+B+2) to 1e-13 (a smoke test against 0, inf, NaN;
# the accuracy itself is tested in tests/quadrature against 60-digit tables).
py=/usr/bin/python3; [ -x "$py" ] || py=python3
for n in 1 2 41 1000; do
  for pq in "30 30" "30 -0.9999999999999999" "-0.9999999999999999 30" "1e-320 -0.5" "-0.9999999999999999 -0.9999999999999999"; do
    set -- $pq
    out="$("$rhabel" rule gauss-jacobi "$n" "$1" "$2")"; rc=$?
    [ "$rc" -eq 0 ] || { fail "n = $n, A B = $pq: exit code $rc"; continue; }
    printf '%s\n' "$out" | "$py" -c '
import math, sys
p, q, n = float(sys.argv[1]), float(sys.argv[2]), int(sys.argv[3])
rows = sys.stdin.read().split()[1:]
w = [float(r.split(",")[3]) for r in rows]
assert len(w) == n, f"{len(w)} nodes"
assert all(math.isfinite(x) and x > 0 for x in w), "a weight is 0, inf or NaN"
mass = 2.0 ** (p + q + 1) * math.gamma(p + 1) * math.gamma(q + 1) / math.gamma(p + q + 2)
assert abs(math.fsum(w) / mass - 1) < 1e-13, f"sum {math.fsum(w)} against {mass}"
' "$1" "$2" "$n" || fail "n = $n, A B = $pq: weights (see above)"
  done
done
set -- "$rhabel"
# Subnormal exponents are in range (1e-320 was refused): the rule of exponent 0; an underflow
# to 0 (1e-400) reads as 0, like the scene's numbers.
zero="$("$rhabel" rule gauss-jacobi 5 0 0.25)"
for tiny in 1e-320 -1e-320 4.9406564584124654e-324 1e-400; do
  out="$("$rhabel" rule gauss-jacobi 5 "$tiny" 0.25)"; rc=$?
  [ "$rc" -eq 0 ] || fail "A = $tiny: exit code $rc"
  paste -d, <(printf '%s\n' "$out" | tail -n +2) <(printf '%s\n' "$zero" | tail -n +2) | awk -F, '
    function abs(v) { return v < 0 ? -v : v }
    { if (abs($4 / $8 - 1) > 1e-14 || abs($2 / $6 - 1) > 1e-14) bad = 1 }
    END { exit bad }' || fail "A = $tiny is not the rule of A = 0"
done

# --- issue 14: a failed write to stdout is exit code 2 with one line, not exit 1 in silence ---
check_write_error() {
  local what="$1"; shift
  local err rc
  err="$( { "$@"; } 2>&1)"; rc=$?
  [ "$rc" -eq 2 ] || fail "$what: exit code $rc (expected 2)"
  [ "$(printf '%s\n' "$err" | wc -l)" -eq 1 ] || fail "$what: message is not one line: $err"
  printf '%s\n' "$err" | grep -q "^rhabel: rule gauss-jacobi: cannot write the rule to stdout" ||
    fail "$what: message: $err"
}
if [ -w /dev/full ]; then
  check_write_error "/dev/full, n = 3" sh -c '"$0" rule gauss-jacobi 3 0 0 > /dev/full' "$rhabel"
  check_write_error "/dev/full, n = 10^5" sh -c '"$0" rule gauss-jacobi 100000 0.25 0 > /dev/full' "$rhabel"
fi
check_write_error "closed stdout" sh -c '"$0" rule gauss-jacobi 3 0 0 >&-' "$rhabel"

# --- issue 14: every message is one line, also when an argument holds a newline -------------
check_bad N rule gauss-jacobi $'3\n4' 0 0
check_bad A rule gauss-jacobi 3 $'0\r\n1' 0
err="$("$rhabel" rule gauss-jacobi 3 0 $'x\ny' 2>&1 >/dev/null)"
printf '%s\n' "$err" | grep -q -F "B = 'x\ny'" || fail "the newline is not shown escaped: $err"
err="$("$rhabel" $'rule\nx' 2>&1 >/dev/null)"; rc=$?
[ "$rc" -eq 2 ] && [ "$(printf '%s\n' "$err" | wc -l)" -eq 1 ] || fail "unknown command with a newline: rc $rc, $err"
err="$("$rhabel" rule gauss-jacobi 3 0 0 $'extra\nword' 2>&1 >/dev/null)"; rc=$?
[ "$rc" -eq 2 ] && [ "$(printf '%s\n' "$err" | wc -l)" -eq 1 ] || fail "extra argument with a newline: rc $rc, $err"
printf '%s\n' "$err" | grep -q "^rhabel: rule gauss-jacobi: " || fail "parse error does not name the command: $err"

# --- exit codes are documented in the help texts ---------------------------------------------
for words in "--help" "rule gauss-jacobi --help"; do
  # shellcheck disable=SC2086
  help="$("$rhabel" $words)" || fail "rhabel $words: exit code $?"
  for line in "^Exit codes:" "^  0  ok" "^  1  internal error" "^  2  bad input, a scene that cannot be solved, or an output that could not be written"; do
    printf '%s\n' "$help" | grep -q "$line" || fail "rhabel $words does not document the exit codes ($line)"
  done
done

# an unknown command is named, exit code 2
err="$("$rhabel" frobnicate 2>&1 >/dev/null)"; rc=$?
[ "$rc" -eq 2 ] || fail "'frobnicate' exit code $rc (expected 2)"
printf '%s\n' "$err" | grep -q "unknown command 'frobnicate'" || fail "'frobnicate' message: $err"

if [ "$failures" -ne 0 ]; then
  echo "$failures check(s) failed"
  exit 1
fi
echo "all rule checks passed"
