#!/usr/bin/env bash
# CLI test of `rhabel fit-material` and of scenes whose material is a master curve:
#   bash test_fit_material.sh <path-to-rhabel-binary> <source-dir>
# Oracles (python3 standard library only, no code shared with rhabel): a curve sampled from
# E* = E1 Gamma(1 - alpha) (i omega)^alpha must give alpha and E1 back to 1e-12; a knee must be
# flagged (exit 3, one warning line); bad curves exit 2 with one line naming row and column; a scene
# with the shipped curve solves, and its fitted omega0 equals U/L of its own result.
set -u
rhabel="$(cd "$(dirname "$1")" && pwd)/$(basename "$1")"; src="$2"
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }
py=/usr/bin/python3; [ -x "$py" ] || py=python3
tmp="$(mktemp -d)"; trap 'rm -rf "$tmp"' EXIT

# --- exact power law: alpha and E1 to 1e-12 (Hz header, E_storage/E_loss) ----------------------
"$py" - "$tmp/exact.csv" <<'PY'
import math, sys
alpha, E1 = 0.27, 3.3e6
with open(sys.argv[1], "w") as f:
    f.write("f_hz,E_storage,E_loss\n")
    for k in range(-20, 81):
        fr = 10 ** (k / 10)
        w = 2 * math.pi * fr
        m = E1 * math.gamma(1 - alpha) * w ** alpha
        f.write(f"{fr!r},{m * math.cos(alpha * math.pi / 2)!r},{m * math.sin(alpha * math.pi / 2)!r}\n")
PY
"$rhabel" fit-material "$tmp/exact.csv" --speed 0.02 --length 1e-3 --json > "$tmp/fit.json" 2> "$tmp/err"; rc=$?
[ "$rc" -eq 0 ] || fail "exact curve: exit code $rc ($(cat "$tmp/err"))"
"$py" - "$tmp/fit.json" <<'PY' || fail "exact curve: fit (see above)"
import json, sys
r = json.load(open(sys.argv[1]))
for k in ("alpha", "E1", "omega0", "alpha_slope", "alpha_tan_delta"):
    assert k in r, f"missing {k}"
assert abs(r["alpha"] - 0.27) <= 1e-12, r["alpha"]
assert abs(r["alpha_tan_delta"] - 0.27) <= 1e-12, r["alpha_tan_delta"]
assert abs(r["E1"] / 3.3e6 - 1) <= 1e-12, r["E1"]
assert r["omega0"] == 20.0 and r["status"] == "ok", r
PY
"$rhabel" fit-material "$tmp/exact.csv" --speed 0.02 --length 1e-3 > "$tmp/text" 2>&1 || fail "text output: exit $?"
grep -q "^alpha  *0.27" "$tmp/text" || fail "text output lacks alpha: $(cat "$tmp/text")"

# --- knee: flagged, exit 3, one warning line on stderr ------------------------------------------
"$py" - "$tmp/knee.csv" <<'PY'
import math, sys
with open(sys.argv[1], "w") as f:
    f.write("omega,E_abs,tan_delta\n")
    for k in range(-30, 91):
        w = 10 ** (k / 10)
        a = 0.1 if w <= 1e3 else 0.45
        m = 2e6 * w ** 0.1 if w <= 1e3 else 2e6 * 1e3 ** 0.1 * (w / 1e3) ** 0.45
        f.write(f"{w!r},{m!r},{math.tan(a * math.pi / 2)!r}\n")
PY
"$rhabel" fit-material "$tmp/knee.csv" --speed 1.5 --length 1e-3 --json > "$tmp/knee.json" 2> "$tmp/err"; rc=$?
[ "$rc" -eq 3 ] || fail "knee: exit code $rc, expected 3"
[ "$(wc -l < "$tmp/err")" -eq 1 ] && grep -q "^rhabel: fit-material: warning: poor_power_law" "$tmp/err" \
  || fail "knee: expected one warning line, got: $(cat "$tmp/err")"
grep -q '"status": "poor_power_law"' "$tmp/knee.json" || fail "knee: status not in the JSON"
"$rhabel" fit-material "$tmp/knee.csv" --speed 100 --length 1e-3 --json > "$tmp/right.json" 2> "$tmp/err"; rc=$?
[ "$rc" -eq 0 ] || fail "knee, right side: exit code $rc ($(cat "$tmp/err"))"
"$py" -c "import json,sys; r=json.load(open(sys.argv[1])); assert abs(r['alpha']-0.45)<=1e-12, r" "$tmp/right.json" \
  || fail "knee, right side: alpha"

# --- bad curves: exit 2, one line naming row and column, nothing on stdout ------------------------
bad() {  # bad NAME EXPECTED-SUBSTRING CSV-TEXT
  printf '%b' "$3" > "$tmp/$1.csv"
  "$rhabel" fit-material "$tmp/$1.csv" --speed 1 --length 1 > "$tmp/out" 2> "$tmp/err"; rc=$?
  [ "$rc" -eq 2 ] || fail "$1: exit code $rc, expected 2"
  [ -s "$tmp/out" ] && fail "$1: something on stdout"
  [ "$(wc -l < "$tmp/err")" -eq 1 ] || fail "$1: expected one line on stderr, got: $(cat "$tmp/err")"
  grep -qF -- "$2" "$tmp/err" || fail "$1: message lacks '$2': $(cat "$tmp/err")"
}
bad two_rows "2 data row(s), at least 3" 'omega,E_storage,E_loss\n1,1,0.1\n2,2,0.1\n'
bad non_monotone "row 4, column 1 (omega)" 'omega,E_storage,E_loss\n1,1,0.1\n3,2,0.1\n2,3,0.1\n'
bad negative "row 3, column 2 (E_storage)" 'omega,E_storage,E_loss\n1,1,0.1\n2,-2,0.1\n3,3,0.1\n'
bad nan "row 3, column 3 (E_loss): 'NaN' is not a finite number" 'omega,E_storage,E_loss\n1,1,0.1\n2,2,NaN\n3,3,0.1\n'
bad unknown "row 1, column 2 ('G_storage'): unknown column" 'omega,G_storage,E_loss\n1,1,0.1\n2,2,0.1\n3,3,0.1\n'
bad extra "row 1, column 4 ('T'): unknown column" 'omega,E_abs,tan_delta,T\n1,1,0.1,0\n'
bad empty "no header line" ''
rm -f "$tmp/missing.csv"
"$rhabel" fit-material "$tmp/missing.csv" --speed 1 --length 1 > /dev/null 2> "$tmp/err"; rc=$?
[ "$rc" -eq 2 ] && grep -q "cannot read master curve" "$tmp/err" || fail "missing file: exit $rc, $(cat "$tmp/err")"
"$rhabel" fit-material "$tmp/exact.csv" --speed 1e9 --length 1e-3 > /dev/null 2> "$tmp/err"; rc=$?
[ "$rc" -eq 2 ] && grep -q "outside the master curve's range" "$tmp/err" || fail "omega0 out of range: exit $rc, $(cat "$tmp/err")"
# Non-numbers and numbers outside an option's range: exit 2, the option named (NaN too, which
# CLI11's own range checks let through).
for opt in "--speed nan" "--speed 0" "--speed inf" "--length nan" "--length -1" "--window-decades nan" "--threshold nan"; do
  set -- $opt
  args=(--speed 0.02 --length 1e-3)
  case "$1" in --speed) args=(--speed "$2" --length 1e-3) ;; --length) args=(--speed 0.02 --length "$2") ;; *) args+=("$1" "$2") ;; esac
  "$rhabel" fit-material "$tmp/exact.csv" "${args[@]}" > /dev/null 2> "$tmp/err"; rc=$?
  [ "$rc" -eq 2 ] && grep -q -- "$1" "$tmp/err" || fail "$opt: exit $rc, $(cat "$tmp/err")"
done
"$rhabel" fit-material "$tmp/exact.csv" --speed 1 --length 1 --temperature 40 > /dev/null 2> "$tmp/err"; rc=$?
[ "$rc" -eq 2 ] || fail "--temperature without --wlf: exit $rc"

# --- WLF through the command line: E1(T) = E1 a_T^alpha on a power law ---------------------------
"$rhabel" fit-material "$tmp/exact.csv" --speed 0.02 --length 1e-3 --temperature 40 --wlf 8.86,101.6,20 --json \
  > "$tmp/hot.json" 2> "$tmp/err" || fail "WLF: exit $? ($(cat "$tmp/err"))"
"$py" - "$tmp/hot.json" <<'PY' || fail "WLF: E1 at 40 degC"
import json, sys
r = json.load(open(sys.argv[1]))
log10_aT = -8.86 * 20 / 121.6                      # by hand: -1.4572368421052631
assert abs(r["log10_aT"] - log10_aT) <= 1e-15, r["log10_aT"]
assert abs(r["E1"] / (3.3e6 * 10 ** (log10_aT * 0.27)) - 1) <= 1e-12, r["E1"]
PY

# --- scenes with a master curve --------------------------------------------------------------
mkdir -p "$tmp/scenes/curves"
cp "$src/examples/materials/filled_rubber.csv" "$tmp/scenes/curves/rubber.csv"
cat > "$tmp/scenes/rubber.json" <<'JSON'
{"material": {"master_curve": "curves/rubber.csv", "temperature": 30.0,
              "wlf": {"C1": 8.86, "C2": 101.6, "T_ref": 20.0}, "nu": 0.5, "coulomb": 0.2},
 "speed": 0.3, "indentors": [{"shape": "parabolic", "radius": 0.01, "load": 500.0}]}
JSON
(cd / && "$rhabel" solve "$tmp/scenes/rubber.json" > "$tmp/rubber_out.json" 2> "$tmp/err"); rc=$?
[ "$rc" -eq 0 ] || fail "master-curve scene: exit code $rc ($(cat "$tmp/err"))"
"$py" - "$tmp/rubber_out.json" <<'PY' || fail "master-curve scene: result (see above)"
import json, sys
r = json.load(open(sys.argv[1]))
f = r["material_fit"]
for k in ("alpha", "E1", "omega0", "alpha_slope", "alpha_tan_delta", "window", "status", "log10_aT"):
    assert k in f, f"missing {k}"
L = r["indentors"][0]["contact_length"]
assert abs(f["omega0"] * L / 0.3 - 1) < 1e-9, (f["omega0"], L)   # the fixed point omega0 = U/L
assert r["scene"]["material"]["alpha"] == f["alpha"] and r["scene"]["material"]["E1"] == f["E1"]
assert f["window"][0] < f["omega0"] < f["window"][1]
assert 0 < f["alpha"] < 1 and f["status"] == "ok"
PY
printf '%s' '{"material": {"master_curve": "curves/rubber.csv", "temperature": 30, "nu": 0.5, "coulomb": 0}, "speed": 1, "indentors": [{"shape": "parabolic", "radius": 0.01, "load": 500}]}' > "$tmp/scenes/no_wlf.json"
"$rhabel" solve "$tmp/scenes/no_wlf.json" > /dev/null 2> "$tmp/err"; rc=$?
[ "$rc" -eq 2 ] && grep -q "material.wlf is missing" "$tmp/err" || fail "temperature without wlf: exit $rc, $(cat "$tmp/err")"
printf '%s' '{"material": {"master_curve": "curves/rubber.csv", "alpha": 0.3, "nu": 0.5, "coulomb": 0}, "speed": 1, "indentors": [{"shape": "parabolic", "radius": 0.01, "load": 500}]}' > "$tmp/scenes/both.json"
"$rhabel" solve "$tmp/scenes/both.json" > /dev/null 2> "$tmp/err"; rc=$?
[ "$rc" -eq 2 ] && grep -q "material.alpha is not a known field of a master-curve material" "$tmp/err" || fail "alpha beside master_curve: exit $rc, $(cat "$tmp/err")"
printf '%s' '{"material": {"master_curve": "nowhere.csv", "nu": 0.5, "coulomb": 0}, "speed": 1, "indentors": [{"shape": "parabolic", "radius": 0.01, "load": 500}]}' > "$tmp/scenes/nowhere.json"
"$rhabel" solve "$tmp/scenes/nowhere.json" > "$tmp/out" 2> "$tmp/err"; rc=$?
[ "$rc" -eq 2 ] && [ ! -s "$tmp/out" ] && grep -q "nowhere.csv" "$tmp/err" || fail "missing curve file: exit $rc, $(cat "$tmp/err")"
# A scene whose fixed point sits next to the knee (omega0 ~ 1.6e3 rad/s, 0.2 decade right of it):
# written, warned, exit 3. At 10 m/s it lies 0.6 decade right of the knee: ok, alpha = 0.45.
cp "$tmp/knee.csv" "$tmp/scenes/knee.csv"
printf '%s' '{"material": {"master_curve": "knee.csv", "nu": 0.5, "coulomb": 0}, "speed": 5, "indentors": [{"shape": "parabolic", "radius": 0.01, "load": 2000}]}' > "$tmp/scenes/knee.json"
"$rhabel" solve "$tmp/scenes/knee.json" > "$tmp/out" 2> "$tmp/err"; rc=$?
"$py" -c "import json,sys; f=json.load(open(sys.argv[1]))['material_fit']; print(f['omega0'], f['alpha_slope'], f['alpha_tan_delta'], f['status'])" "$tmp/out" > "$tmp/knee_fit"
[ "$rc" -eq 3 ] && grep -q "poor_power_law" "$tmp/knee_fit" && grep -q "^rhabel: solve: warning: poor_power_law" "$tmp/err" \
  || fail "knee scene: exit $rc, fit $(cat "$tmp/knee_fit"), stderr $(cat "$tmp/err")"

sed -i 's/"speed": 5,/"speed": 10,/' "$tmp/scenes/knee.json"
"$rhabel" solve "$tmp/scenes/knee.json" > "$tmp/out" 2> "$tmp/err"; rc=$?
[ "$rc" -eq 0 ] && [ ! -s "$tmp/err" ] || fail "knee scene right of the knee: exit $rc, $(cat "$tmp/err")"

[ "$failures" -eq 0 ] && echo "test_fit_material: all checks passed"
exit $(( failures > 0 ))
