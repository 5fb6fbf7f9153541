#!/usr/bin/env bash
# CLI test of hostile but realistic input (issue 31), each case a clean refusal or a correct result:
#   bash test_hostile_input.sh <path-to-rhabel-binary> <source-dir>
# A refusal is exit 2 with one line on stderr naming the field, option or file, and nothing
# written. Files that are not regular files (a directory, /dev/zero, a FIFO without a writer, a
# file with a NUL in its name) are refused at once, never read (each command runs under `timeout`
# so that a regression fails instead of hanging the suite).
set -u
rhabel="$(cd "$(dirname "$1")" && pwd)/$(basename "$1")"; src="$(cd "$2" && pwd)"
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }
py=/usr/bin/python3; [ -x "$py" ] || py=python3
tmp="$(mktemp -d)"; trap 'rm -rf "$tmp"' EXIT
limit=60  # seconds: far above every command here (each takes well under one)
curve="$src/examples/materials/filled_rubber.csv"

# refused NAME EXPECTED -- COMMAND...: exit 2, one line on stderr containing EXPECTED, nothing on stdout.
refused() {
  local name="$1" expected="$2"; shift 3
  timeout "$limit" "$@" > "$tmp/out" 2> "$tmp/err"; local rc=$?
  [ "$rc" -eq 2 ] || { fail "$name: exit $rc, expected 2 ($(head -c 300 "$tmp/err"))"; return; }
  [ "$(wc -l < "$tmp/err")" -eq 1 ] || fail "$name: not one line on stderr: $(head -c 300 "$tmp/err")"
  grep -qF -- "$expected" "$tmp/err" || fail "$name: message does not name '$expected': $(cat "$tmp/err")"
  [ -s "$tmp/out" ] && fail "$name: something on stdout"
  grep -q "internal error\|basic_filebuf\|bad_alloc" "$tmp/err" && fail "$name: raw library message: $(cat "$tmp/err")"
}

scene_with_curve() {  # FILE MASTER_CURVE_JSON_STRING
  printf '{"material": {"master_curve": %s, "nu": 0.5, "coulomb": 0.3}, "speed": 0.01,
  "indentors": [{"shape": "parabolic", "radius": 0.01, "load": 500}]}' "$2" > "$1"
}

# --- master curves that are not regular files -----------------------------------------------------
mkdir "$tmp/curve_dir"
mkfifo "$tmp/curve_fifo"
for target in "$tmp/curve_dir" /dev/zero "$tmp/curve_fifo"; do
  name=$(basename "$target")
  refused "fit-material $name" "$target" -- "$rhabel" fit-material "$target" --speed 0.01 --length 0.001
  scene_with_curve "$tmp/s_$name.json" "\"$target\""
  refused "solve $name" "$target" -- "$rhabel" solve "$tmp/s_$name.json"
  printf '{"scene": "s_%s.json", "axes": [{"path": "speed", "values": [0.01, 0.1]}]}' "$name" > "$tmp/w_$name.json"
  refused "sweep $name" "$target" -- "$rhabel" sweep "$tmp/w_$name.json" --out "$tmp/w_$name.csv"
  [ -e "$tmp/w_$name.csv" ] && fail "sweep $name: an output file was created"
done
# a scene or sweep file that is a device or a FIFO
refused "solve /dev/zero" "scene file '/dev/zero'" -- "$rhabel" solve /dev/zero
refused "sweep /dev/zero" "/dev/zero" -- "$rhabel" sweep /dev/zero --out "$tmp/z.csv"
printf '{"scene": "/dev/zero", "axes": [{"path": "speed", "values": [1]}]}' > "$tmp/w_zero_scene.json"
refused "sweep scene /dev/zero" "scene file '/dev/zero'" -- "$rhabel" sweep "$tmp/w_zero_scene.json" --out "$tmp/z.csv"

# --- a NUL byte in a master-curve name; hex floats; byte-order marks -------------------------------
cp "$curve" "$tmp/c.csv"
scene_with_curve "$tmp/nul.json" '"c.csv\u0000junk"'
refused "master_curve with NUL" "material.master_curve" -- "$rhabel" solve "$tmp/nul.json"
printf 'omega,E_abs,tan_delta\n1,1e6,0.1\n10,0x1p+23,0.1\n100,1e7,0.1\n' > "$tmp/hex.csv"
refused "hex float" "row 3, column 2 (E_abs): '0x1p+23' is a hexadecimal number" -- \
  "$rhabel" fit-material "$tmp/hex.csv" --speed 1 --length 0.1
# A UTF-8 byte-order mark at the start: skipped (the one rule of master-curve and profile CSVs).
printf '\xef\xbb\xbf' | cat - "$curve" > "$tmp/bom.csv"
timeout "$limit" "$rhabel" fit-material "$curve" --speed 0.01 --length 0.001 --json > "$tmp/plain.json" 2> /dev/null
timeout "$limit" "$rhabel" fit-material "$tmp/bom.csv" --speed 0.01 --length 0.001 --json > "$tmp/bom.json" 2> "$tmp/err" \
  || [ $? -eq 3 ] || fail "master curve with a BOM: exit $? ($(cat "$tmp/err"))"
"$py" - "$tmp/plain.json" "$tmp/bom.json" <<'PY' || fail "master curve with a BOM: fit differs from the plain file"
import json, sys
a, b = (json.load(open(p)) for p in sys.argv[1:])
assert a["alpha"] == b["alpha"] and a["E1"] == b["E1"], (a, b)
PY
samples='0,-4e-6\n0.001,-1e-6\n0.002,0\n0.003,-1e-6\n0.004,-4e-6\n'
printf "\xef\xbb\xbf$samples" > "$tmp/bom_profile.csv"
printf "$samples" > "$tmp/plain_profile.csv"
for p in bom plain; do
  printf '{"material": {"alpha": 0.3, "E1": 1e6, "nu": 0.5, "coulomb": 0}, "speed": 0.01, "body": {"load": 10},
  "profile": {"file": "%s_profile.csv"}}' "$p" > "$tmp/p_$p.json"
  timeout "$limit" "$rhabel" solve "$tmp/p_$p.json" > "$tmp/p_$p.out" 2> "$tmp/p_$p.err"; echo $? > "$tmp/p_$p.rc"
done
grep -q '"samples": 5' "$tmp/p_bom.out" || fail "profile with a BOM: the first sample was lost ($(head -c 300 "$tmp/p_bom.out") $(cat "$tmp/p_bom.err"))"
cmp -s "$tmp/p_bom.rc" "$tmp/p_plain.rc" || fail "profile with a BOM: exit $(cat "$tmp/p_bom.rc"), plain $(cat "$tmp/p_plain.rc")"

# --- a single flat punch with a master-curve material: the contact length is the flat's width ------
printf '{"material": {"master_curve": "%s", "nu": 0.5, "coulomb": 0.3}, "speed": 0.01,
  "indentors": [{"shape": "flat", "width": 0.004, "load": 200}]}' "$curve" > "$tmp/flat.json"
timeout "$limit" "$rhabel" solve "$tmp/flat.json" > "$tmp/flat.out" 2> "$tmp/err"; rc=$?
[ "$rc" -eq 0 ] || [ "$rc" -eq 3 ] || fail "single flat with a master curve: exit $rc ($(cat "$tmp/err"))"
"$py" - "$tmp/flat.out" <<'PY' || fail "single flat with a master curve: fit (see above)"
import json, sys
r = json.load(open(sys.argv[1]))
fit = r["material_fit"]
assert fit["contact_length"] == 0.004, fit
assert abs(fit["omega0"] - 0.01 / 0.004) < 1e-9 * fit["omega0"], fit
PY

# --- sweep axes that are not scene fields ----------------------------------------------------------
scene='{"material": {"alpha": 0.3, "E1": 1e6, "nu": 0.3, "coulomb": 0}, "speed": 1, "indentors": [{"shape": "flat", "width": 0.01, "load": 1}]}'
bad_axis() {  # NAME EXPECTED PATH_JSON
  printf '{"scene": %s, "axes": [{"path": %s, "values": [1, 2]}]}' "$scene" "$3" > "$tmp/$1.json"
  refused "$1" "$2" -- "$rhabel" sweep "$tmp/$1.json" --out "$tmp/$1.csv"
  [ -e "$tmp/$1.csv" ] && fail "$1: an output file was created"
}
bad_axis huge_index 'sweep: axes[0].path = "indentors[99999999999999999999].load"' '"indentors[99999999999999999999].load"'
bad_axis far_index 'sweep: axes[0].path = "indentors[7].load"' '"indentors[7].load"'
bad_axis unknown_field 'sweep: axes[0].path = "material.temprature" is not a field of the scene' '"material.temprature"'
bad_axis unknown_top 'sweep: axes[0].path = "sped" is not a field of the scene' '"sped"'
bad_axis nul_path 'sweep: axes[0].path' '"speed\u0000x"'
# a field the base scene lacks but the scene knows is fine (an indentor's apex)
printf '{"scene": %s, "axes": [{"path": "indentors[0].apex", "values": [0, 0.1]}]}' "$scene" > "$tmp/apex.json"
timeout "$limit" "$rhabel" sweep "$tmp/apex.json" --out "$tmp/apex.csv" 2> "$tmp/err" || fail "apex axis: exit $? ($(cat "$tmp/err"))"

# --- range near the ends of the double range: the middle value is 0 ---------------------------------
printf '{"scene": %s, "axes": [{"path": "indentors[0].apex", "range": {"from": -1e308, "to": 1e308, "count": 3}}]}' \
  "$scene" > "$tmp/huge_range.json"
timeout "$limit" "$rhabel" sweep "$tmp/huge_range.json" --print-scenes > "$tmp/scenes" 2> "$tmp/err" || fail "huge range: exit $?"
"$py" - "$tmp/scenes" <<'PY' || fail "huge range: the middle value (see above)"
import json, sys
apex = [json.loads(l)["indentors"][0]["apex"] for l in open(sys.argv[1])]
assert apex == [-1e308, 0.0, 1e308], apex
PY

# --- --out that is not a regular file -------------------------------------------------------------
printf '{"scene": %s, "axes": [{"path": "speed", "values": [1, 2]}]}' "$scene" > "$tmp/small.json"
mkdir "$tmp/out_dir"; mkfifo "$tmp/out_fifo"
for target in /dev/full "$tmp/out_dir" "$tmp/out_fifo"; do
  refused "--out $(basename "$target")" "sweep: --out $target" -- "$rhabel" sweep "$tmp/small.json" --out "$target"
done

# --- resume: a torn line in the middle of the partial output is dropped and solved again ------------
printf '{"scene": %s, "axes": [{"path": "speed", "values": [1, 2, 3, 4, 5]}]}' "$scene" > "$tmp/five.json"
timeout "$limit" "$rhabel" sweep "$tmp/five.json" --out "$tmp/full.csv" 2> /dev/null || fail "five rows: exit $?"
timeout "$limit" "$rhabel" sweep "$tmp/five.json" --out "$tmp/full.jsonl" --jsonl 2> /dev/null || fail "five rows jsonl: exit $?"
"$py" - "$tmp" <<'PY'
import sys
d = sys.argv[1]
for ext in ("csv", "jsonl"):
    lines = open(f"{d}/full.{ext}").read().splitlines(keepends=True)
    head = 1 if ext == "csv" else 0
    rows = lines[head:]
    # row 1 torn after 13 fields (a killed writer), then rows 3 and 0 complete; row 2 cut in its prefix
    torn = rows[1][: len(rows[1]) // 2].rstrip("\n") + "\n"
    cut = rows[2][:2] + "\n"
    open(f"{d}/torn.{ext}", "w").write("".join(lines[:head]) + torn + rows[3] + cut + rows[0])
PY
for ext in csv jsonl; do
  flag=""; [ "$ext" = jsonl ] && flag=--jsonl
  timeout "$limit" "$rhabel" sweep "$tmp/five.json" --out "$tmp/torn.$ext" $flag 2> "$tmp/err" \
    || fail "torn $ext: exit $? ($(cat "$tmp/err"))"
  "$py" - "$tmp/torn.$ext" "$tmp/full.$ext" <<'PY' || fail "torn $ext: the torn line was kept (see above)"
import csv, json, sys
def load(p):
    if p.endswith(".jsonl"):
        rows = [json.loads(l) for l in open(p)]
    else:
        rows = list(csv.DictReader(open(p, newline="")))
    for r in rows:
        r.pop("seconds")
    return rows
a, b = (load(p) for p in sys.argv[1:])
assert [int(r["row"]) for r in a] == list(range(5)), a
assert a == b, (a, b)
PY
done

[ "$failures" -eq 0 ] && echo "hostile_input: all checks passed"
exit $(( failures > 0 ))
