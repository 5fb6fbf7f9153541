#!/usr/bin/env bash
# CLI test of `rhabel sweep`:
#   bash test_sweep.sh <path-to-rhabel-binary> <source-dir>
# Oracles: each row against a separate `rhabel solve` of that row's scene (bit for bit: the CSV
# numbers parsed as doubles equal the JSON ones), CSV against JSON lines, 1 thread against 2, a run
# killed with SIGKILL part-way (plus a torn last line) and rerun against an uninterrupted run (every
# row exactly once, in order). The `seconds` column is the only one allowed to differ between runs.
set -u
rhabel="$(cd "$(dirname "$1")" && pwd)/$(basename "$1")"; src="$2"
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }
py=/usr/bin/python3; [ -x "$py" ] || py=python3
tmp="$(mktemp -d)"; trap 'rm -rf "$tmp"' EXIT

# Same rows apart from the seconds column (CSV or JSON lines), every row once, in order.
same_rows() {
  "$py" - "$1" "$2" <<'PY'
import csv, json, sys
def load(p):
    if p.endswith(".jsonl"):
        rows = [json.loads(l) for l in open(p)]
        return [{k: v for k, v in r.items() if k != "seconds"} for r in rows]
    rows = list(csv.DictReader(open(p, newline="")))
    for r in rows:
        r.pop("seconds")
    return rows
a, b = load(sys.argv[1]), load(sys.argv[2])
ia = [int(r["row"]) for r in a]
assert ia == list(range(len(a))), f"{sys.argv[1]}: rows not 0..n-1 in order"
assert len(a) == len(b), (len(a), len(b))
for x, y in zip(a, b):
    assert x == y, f"differ:\n{x}\n{y}"
PY
}

cat > "$tmp/wedges.json" <<'JSON'
{"scene": {"material": {"alpha": 0.3, "E1": 1.0e6, "nu": 0.3, "coulomb": 0.5}, "speed": 0.01,
           "indentors": [{"shape": "wedge", "slope_leading": 0.05, "slope_trailing": 0.08, "load": 100.0},
                         {"shape": "parabolic", "radius": 0.02, "load": 50.0, "apex": 0.05}]},
 "axes": [{"path": "speed", "log_range": {"from": 1e-3, "to": 10, "count": 4}},
          {"path": "material.alpha", "values": [0.0, 0.25, 0.6]},
          {"path": "indentors[1].load", "values": [50.0, -1]}]}
JSON

# --- rows equal single solves, bit for bit; a failed row is a row -------------------------------
"$rhabel" sweep "$tmp/wedges.json" --out "$tmp/w.csv" > "$tmp/out" 2> "$tmp/err"; rc=$?
[ "$rc" -eq 3 ] || fail "sweep with invalid rows: exit $rc, expected 3 ($(cat "$tmp/err"))"
[ -s "$tmp/out" ] && fail "sweep wrote to stdout"
[ -s "$tmp/err" ] && fail "sweep wrote to stderr without a terminal: $(cat "$tmp/err")"
"$rhabel" sweep "$tmp/wedges.json" --print-scenes > "$tmp/scenes.jsonl" || fail "--print-scenes: exit $?"
[ "$(wc -l < "$tmp/scenes.jsonl")" -eq 24 ] || fail "--print-scenes: expected 24 scenes"
mkdir "$tmp/single"
i=0
while IFS= read -r scene; do
  printf '%s' "$scene" > "$tmp/single/$i.json"
  "$rhabel" solve "$tmp/single/$i.json" --compact > "$tmp/single/$i.out" 2> "$tmp/single/$i.err"
  echo $? > "$tmp/single/$i.rc"
  i=$((i + 1))
done < "$tmp/scenes.jsonl"
"$py" - "$tmp/w.csv" "$tmp/single" <<'PY' || fail "rows against single solves (see above)"
import csv, json, os, sys
rows = list(csv.DictReader(open(sys.argv[1], newline="")))
assert len(rows) == 24
d = sys.argv[2]
ok = bad = 0
for r in rows:
    i = int(r["row"])
    rc = int(open(os.path.join(d, f"{i}.rc")).read())
    if r["status"] == "invalid_scene":
        assert rc == 2, (i, rc)
        err = open(os.path.join(d, f"{i}.err")).read().strip()
        assert err == "rhabel: " + r["message"], (err, r["message"])
        assert float(r["indentors[1].load"]) == -1
        bad += 1
        continue
    res = json.load(open(os.path.join(d, f"{i}.out")))
    assert r["status"] == res["diagnostics"]["status"]
    assert (rc == 0) == (r["status"] == "ok")
    assert float(r["alpha"]) == res["scene"]["material"]["alpha"]
    assert float(r["residual"]) == res["diagnostics"]["residual"]
    for k, ind in enumerate(res["indentors"]):
        p = f"ind{k}_"
        assert float(r[p + "a"]) == ind["contact"][0] and float(r[p + "b"]) == ind["contact"][1], i
        assert float(r[p + "contact_length"]) == ind["contact_length"]
        assert float(r[p + "load"]) == ind["load"]
        assert float(r[p + "C_f"]) == ind["hysteretic_friction"], (i, r[p + "C_f"], ind["hysteretic_friction"])
        assert float(r[p + "total_friction"]) == ind["total_friction"]
    ok += 1
assert ok == 12 and bad == 12, (ok, bad)
PY

# --- JSON lines = CSV; 1 thread = 2 threads ----------------------------------------------------
"$rhabel" sweep "$tmp/wedges.json" --out "$tmp/w.jsonl" --jsonl --threads 1 2> "$tmp/err"
[ $? -eq 3 ] || fail "jsonl: exit code ($(cat "$tmp/err"))"
"$py" - "$tmp/w.csv" "$tmp/w.jsonl" <<'PY' || fail "JSON lines differ from CSV"
import csv, json, sys
c = list(csv.DictReader(open(sys.argv[1], newline="")))
j = [json.loads(l) for l in open(sys.argv[2])]
assert len(c) == len(j)
for x, y in zip(c, j):
    assert list(x) == list(y), (list(x), list(y))
    for k in x:
        if k == "seconds":
            continue
        v = y[k]
        if v is None:
            assert x[k] == "", (k, x[k])
        elif isinstance(v, str):
            assert x[k] == v, (k, x[k], v)
        else:
            assert float(x[k]) == v, (k, x[k], v)
PY
"$rhabel" sweep "$tmp/wedges.json" --out "$tmp/w1.csv" --threads 1 2> /dev/null
"$rhabel" sweep "$tmp/wedges.json" --out "$tmp/w2.csv" --threads 2 2> /dev/null
same_rows "$tmp/w1.csv" "$tmp/w2.csv" || fail "1 thread and 2 threads differ"
same_rows "$tmp/w.csv" "$tmp/w1.csv" || fail "two runs differ"

# --- master-curve sweep (zip of speed and temperature) ------------------------------------------
cat > "$tmp/rubber.json" <<JSON
{"scene": {"material": {"master_curve": "$src/examples/materials/filled_rubber.csv", "temperature": 20,
                        "wlf": {"C1": 8.86, "C2": 101.6, "T_ref": 20}, "nu": 0.5, "coulomb": 0.3},
           "speed": 0.01, "indentors": [{"shape": "parabolic", "radius": 0.01, "load": 500}]},
 "axes": [{"path": "speed", "log_range": {"from": 1e-4, "to": 1, "count": 3}},
          {"path": "material.temperature", "values": [0, 20, 40]}], "combine": "zip"}
JSON
"$rhabel" sweep "$tmp/rubber.json" --out "$tmp/r.csv" 2> "$tmp/err"; rc=$?
[ "$rc" -eq 0 ] || fail "master-curve sweep: exit $rc ($(cat "$tmp/err"))"
"$rhabel" sweep "$tmp/rubber.json" --print-scenes | sed -n 3p > "$tmp/r2.json"
"$rhabel" solve "$tmp/r2.json" --compact > "$tmp/r2.out" || fail "master-curve row 2: solve"
"$py" - "$tmp/r.csv" "$tmp/r2.out" <<'PY' || fail "master-curve row 2 against its single solve"
import csv, json, sys
r = list(csv.DictReader(open(sys.argv[1], newline="")))
assert len(r) == 3 and r[2]["speed"] == "1.0" and r[2]["material.temperature"] == "40"
s = json.load(open(sys.argv[2]))
f = s["material_fit"]
assert float(r[2]["omega0"]) == f["omega0"] and float(r[2]["alpha"]) == f["alpha"] and float(r[2]["E1"]) == f["E1"]
assert float(r[2]["ind0_C_f"]) == s["indentors"][0]["hysteretic_friction"]
PY

# --- a rough periodic profile on the measured rubber: friction against speed, one sweep ------------
# Its profile.file is relative to the example's directory (made absolute for every row); each row
# equals its single solve bit for bit (the boundary-element solver's C_f with its error estimate).
"$py" - "$src/examples/rough_periodic.json" "$tmp/rough_scene.json" <<'PY'
import json, sys
s = json.load(open(sys.argv[1]))
s["material"] = {"master_curve": "materials/filled_rubber.csv", "nu": 0.5, "coulomb": 0.0}
s["profile"]["file"] = "rough_periodic.csv"
json.dump(s, open(sys.argv[2], "w"))
PY
cp "$src/examples/rough_periodic.csv" "$tmp/" && mkdir -p "$tmp/materials" && cp "$src/examples/materials/filled_rubber.csv" "$tmp/materials/"
printf '%s' '{"scene": "rough_scene.json", "axes": [{"path": "speed", "values": [0.01, 1.0]}]}' > "$tmp/rough.json"
"$rhabel" sweep "$tmp/rough.json" --out "$tmp/rough.csv" --acceptance 1e-3 2> "$tmp/err"; rc=$?
[ "$rc" -eq 0 ] || fail "rough-profile sweep: exit $rc ($(cat "$tmp/err"))"
"$rhabel" sweep "$tmp/rough.json" --print-scenes | sed -n 2p > "$tmp/rough_row1.json"
(cd "$tmp" && "$rhabel" solve rough_row1.json --acceptance 1e-3 --compact > rough_row1.out) || fail "rough-profile row 1: solve"
"$py" - "$tmp/rough.csv" "$tmp/rough_row1.out" <<'PY' || fail "rough-profile row 1 against its single solve"
import csv, json, sys
r = list(csv.DictReader(open(sys.argv[1], newline="")))
assert len(r) == 2 and all(x["status"] == "ok" for x in r), r
s = json.load(open(sys.argv[2]))
assert float(r[1]["C_f"]) == s["hysteretic_friction"]["value"] and float(r[1]["C_f_error"]) == s["hysteretic_friction"]["error"]
assert int(r[1]["contacts"]) == len(s["patches"]) and float(r[1]["omega0"]) == s["material_fit"]["omega0"]
assert float(r[0]["C_f"]) != float(r[1]["C_f"])  # the rubber's response differs over two decades
PY

# --- killed part-way (SIGKILL) and rerun: every row exactly once ----------------------------------
cat > "$tmp/long.json" <<'JSON'
{"scene": {"material": {"alpha": 0.3, "E1": 1.0e6, "nu": 0.3, "coulomb": 0.5}, "speed": 0.01,
           "indentors": [{"shape": "parabolic", "radius": 0.01, "load": 100.0}]},
 "axes": [{"path": "indentors[0].load", "log_range": {"from": 10, "to": 1000, "count": 400}},
          {"path": "material.alpha", "range": {"from": 0.05, "to": 0.45, "count": 20}}]}
JSON
"$rhabel" sweep "$tmp/long.json" --out "$tmp/full.csv" --threads 2 2> /dev/null || fail "uninterrupted long sweep: exit $?"
"$rhabel" sweep "$tmp/long.json" --out "$tmp/killed.csv" --threads 2 2> /dev/null &
pid=$!
for _ in $(seq 1 2000); do
  [ -f "$tmp/killed.csv" ] && [ "$(wc -l < "$tmp/killed.csv")" -ge 300 ] && break
  sleep 0.005
done
kill -9 "$pid" 2> /dev/null; wait "$pid" 2> /dev/null
lines=$(wc -l < "$tmp/killed.csv")
echo "killed the first run at $lines lines of 8001"
[ "$lines" -lt 8001 ] || fail "the run finished before it was killed ($lines lines): the test proves nothing"
printf '17,12.3' >> "$tmp/killed.csv"   # a torn last line, as a kill during a write would leave
"$rhabel" sweep "$tmp/long.json" --out "$tmp/killed.csv" --threads 2 2> "$tmp/err"; rc=$?
[ "$rc" -eq 0 ] || fail "rerun after kill: exit $rc ($(cat "$tmp/err"))"
same_rows "$tmp/killed.csv" "$tmp/full.csv" || fail "killed and rerun differs from the uninterrupted run (killed at $lines lines)"
cp "$tmp/killed.csv" "$tmp/before.csv"
"$rhabel" sweep "$tmp/long.json" --out "$tmp/killed.csv" 2> /dev/null || fail "rerun of a complete sweep: exit $?"
cmp -s "$tmp/killed.csv" "$tmp/before.csv" || fail "rerunning a complete sweep changed the file"

# --- another sweep's file is refused; bad sweep files --------------------------------------------
cp "$tmp/full.csv" "$tmp/full_before.csv"
"$rhabel" sweep "$tmp/wedges.json" --out "$tmp/full.csv" > /dev/null 2> "$tmp/err"; rc=$?
[ "$rc" -eq 2 ] && grep -q "exists with another header" "$tmp/err" || fail "foreign file: exit $rc, $(cat "$tmp/err")"
cmp -s "$tmp/full.csv" "$tmp/full_before.csv" || fail "a refused run changed the foreign file"
head -1 "$tmp/full.csv" > "$tmp/foreign.csv"; echo "0,99.0,0.05,ok" >> "$tmp/foreign.csv"
"$rhabel" sweep "$tmp/long.json" --out "$tmp/foreign.csv" > /dev/null 2> "$tmp/err"; rc=$?
[ "$rc" -eq 2 ] && grep -q "line 2 is not a row of this sweep" "$tmp/err" || fail "foreign row: exit $rc, $(cat "$tmp/err")"
bad_sweep() {  # NAME EXPECTED JSON
  printf '%s' "$3" > "$tmp/$1.json"
  "$rhabel" sweep "$tmp/$1.json" --out "$tmp/$1.csv" > /dev/null 2> "$tmp/err"; rc=$?
  [ "$rc" -eq 2 ] || fail "$1: exit $rc, expected 2"
  [ "$(wc -l < "$tmp/err")" -eq 1 ] && grep -qF -- "$2" "$tmp/err" || fail "$1: message: $(cat "$tmp/err")"
  [ -e "$tmp/$1.csv" ] && fail "$1: an output file was created"
}
scene='{"material": {"alpha": 0.3, "E1": 1e6, "nu": 0.3, "coulomb": 0}, "speed": 1, "indentors": [{"shape": "flat", "width": 0.01, "load": 1}]}'
bad_sweep no_axes "axes must be a non-empty array" "{\"scene\": $scene, \"axes\": []}"
bad_sweep bad_path "its parent does not exist" "{\"scene\": $scene, \"axes\": [{\"path\": \"indentors[3].load\", \"values\": [1]}]}"
bad_sweep not_scalar "is not a scalar field" "{\"scene\": $scene, \"axes\": [{\"path\": \"material\", \"values\": [1]}]}"
bad_sweep zip_lengths "combine \"zip\" needs axes of one length" "{\"scene\": $scene, \"combine\": \"zip\", \"axes\": [{\"path\": \"speed\", \"values\": [1, 2]}, {\"path\": \"material.nu\", \"values\": [0.1]}]}"
bad_sweep log_zero "from and to must be > 0" "{\"scene\": $scene, \"axes\": [{\"path\": \"speed\", \"log_range\": {\"from\": 0, \"to\": 1, \"count\": 3}}]}"
bad_sweep bad_scene "sweep: scene: material.nu = 0.7" "{\"scene\": {\"material\": {\"alpha\": 0.3, \"E1\": 1e6, \"nu\": 0.7, \"coulomb\": 0}, \"speed\": 1, \"indentors\": [{\"shape\": \"flat\", \"width\": 0.01, \"load\": 1}]}, \"axes\": [{\"path\": \"speed\", \"values\": [1]}]}"
printf 'omega,E_storage,E_loss\n1,1,0\n2,2,0\n2,3,0\n' > "$tmp/broken_curve.csv"
bad_sweep bad_curve "row 4, column 1 (omega)" "{\"scene\": {\"material\": {\"master_curve\": \"broken_curve.csv\", \"nu\": 0.5, \"coulomb\": 0}, \"speed\": 1, \"indentors\": [{\"shape\": \"flat\", \"width\": 0.01, \"load\": 1}]}, \"axes\": [{\"path\": \"speed\", \"values\": [1]}]}"
bad_sweep unknown "sweeps is not a known field" "{\"scene\": $scene, \"sweeps\": 1, \"axes\": [{\"path\": \"speed\", \"values\": [1]}]}"

# --- --time-limit: every row of several contacts stops there, and says so; bad values refused -----
cat > "$tmp/two.json" <<'JSON'
{"scene": {"material": {"alpha": 0.3, "E1": 1.0, "nu": 0.0, "coulomb": 0.0}, "speed": 1.0,
           "indentors": [{"shape": "parabolic", "radius": 1.0, "load": 0.6, "apex": 0.0},
                         {"shape": "parabolic", "radius": 1.0, "load": 0.6, "apex": 0.9}]},
 "axes": [{"path": "material.alpha", "values": [0.3, 0.5]}]}
JSON
"$rhabel" sweep "$tmp/two.json" --out "$tmp/limited.csv" --time-limit 1e-9 2> "$tmp/err"; rc=$?
[ "$rc" -eq 3 ] || fail "--time-limit 1e-9: exit $rc, expected 3 ($(cat "$tmp/err"))"
"$py" - "$tmp/limited.csv" <<'PY' || fail "--time-limit 1e-9: rows (see above)"
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1], newline="")))
assert len(rows) == 2, rows
for r in rows:
    assert r["status"] == "not_converged" and "time limit" in r["message"], r
PY
"$rhabel" sweep "$tmp/two.json" --out "$tmp/unlimited.csv" --time-limit 0 2> "$tmp/err" \
  || fail "--time-limit 0: exit $? ($(cat "$tmp/err"))"
for limit in -1 nan inf; do
  "$rhabel" sweep "$tmp/two.json" --out "$tmp/bad_limit.csv" --time-limit "$limit" > /dev/null 2> "$tmp/err"; rc=$?
  [ "$rc" -eq 2 ] && grep -q -- "--time-limit" "$tmp/err" && [ ! -e "$tmp/bad_limit.csv" ] \
    || fail "--time-limit $limit: rc $rc, $(cat "$tmp/err")"
done

# --- --tolerance and --acceptance reach every row, which still equals `rhabel solve` with them bit for
# bit; --threads 0 is every core; bad values refused ----------------------------------------------
"$rhabel" sweep "$tmp/two.json" --out "$tmp/tol.csv" --tolerance 1e-6 --acceptance 1e-4 --threads 0 2> "$tmp/err" \
  || fail "--tolerance 1e-6 --acceptance 1e-4 --threads 0: exit $? ($(cat "$tmp/err"))"
"$rhabel" sweep "$tmp/two.json" --print-scenes | head -1 > "$tmp/tol_scene.json"
"$rhabel" solve "$tmp/tol_scene.json" --tolerance 1e-6 --acceptance 1e-4 --compact > "$tmp/tol_solve.json" \
  || fail "solve --tolerance 1e-6 --acceptance 1e-4: exit $?"
# At the default acceptance (1e-9) the same rows are not ok: the acceptance reached them too.
"$rhabel" sweep "$tmp/two.json" --out "$tmp/tol_strict.csv" --tolerance 1e-6 2> /dev/null; rc=$?
[ "$rc" -eq 3 ] || fail "--tolerance 1e-6 at the default acceptance: exit $rc, expected 3"
"$py" - "$tmp/tol.csv" "$tmp/tol_solve.json" "$tmp/unlimited.csv" <<'PY' || fail "--tolerance rows (see above)"
import csv, json, sys
row = list(csv.DictReader(open(sys.argv[1], newline="")))[0]
solve = json.load(open(sys.argv[2]))
default = list(csv.DictReader(open(sys.argv[3], newline="")))[0]
assert row["status"] == solve["diagnostics"]["status"] == "ok", (row, solve["diagnostics"])
for k, ind in enumerate(solve["indentors"]):
    assert float(row[f"ind{k}_C_f"]) == ind["hysteretic_friction"], (row, ind)
    assert float(row[f"ind{k}_a"]) == ind["contact"][0] and float(row[f"ind{k}_b"]) == ind["contact"][1]
# The tolerance reached the solver: the rows differ from the default's (1e-12), by little.
cf, cf0 = float(row["ind0_C_f"]), float(default["ind0_C_f"])
assert cf != cf0 and abs(cf - cf0) < 1e-4 * abs(cf0), (cf, cf0)
PY
# --- --profile-knots reaches every row: the rough example at acceptance 1e-11 is ok with it (its
# spline's knots in the densities; test_solve.sh measures the single solve) and not ok without (the
# series alone ends at residual ~4.5e-10: exit 3); each row equals `rhabel solve --profile-knots` --
printf '{"scene": "%s", "axes": [{"path": "body.load", "values": [5.0, 4.0]}]}' "$src/examples/rough_profile.json" \
  > "$tmp/knots.json"
"$rhabel" sweep "$tmp/knots.json" --out "$tmp/knots.csv" --acceptance 1e-11 --profile-knots 2> "$tmp/err"; rc=$?
[ "$rc" -eq 0 ] || fail "--profile-knots at acceptance 1e-11: exit $rc ($(cat "$tmp/err"))"
"$rhabel" sweep "$tmp/knots.json" --out "$tmp/plain.csv" --acceptance 1e-11 2> /dev/null; rc=$?
[ "$rc" -eq 3 ] || fail "the same sweep without --profile-knots: exit $rc, expected 3"
"$rhabel" sweep "$tmp/knots.json" --print-scenes | sed -n 2p > "$tmp/knots_row1.json"
"$rhabel" solve "$tmp/knots_row1.json" --acceptance 1e-11 --profile-knots --compact > "$tmp/knots_row1.out" \
  || fail "row 1 solved with --profile-knots: exit $?"
"$py" - "$tmp/knots.csv" "$tmp/knots_row1.out" <<'PY' || fail "--profile-knots rows (see above)"
import csv, json, sys
rows = list(csv.DictReader(open(sys.argv[1], newline="")))
assert [r["status"] for r in rows] == ["ok", "ok"], rows
s = json.load(open(sys.argv[2]))
assert float(rows[1]["C_f"]) == s["hysteretic_friction"] and int(rows[1]["contacts"]) == len(s["contacts"]), (rows[1], s)
assert float(rows[1]["residual"]) == s["diagnostics"]["residual"] <= 1e-11
PY
# --- every row records its solve options, and a file is resumed only under the same ones: another
# --acceptance, --tolerance or --profile-knots is refused (exit 2, naming both, the file untouched);
# --time-limit (a budget, not a bar) may change -----------------------------------------------------
"$py" - "$tmp/tol.csv" "$tmp/unlimited.csv" "$tmp/knots.csv" <<'PY' || fail "the rows' option columns (see above)"
import csv, sys
tol, default, knots = (list(csv.DictReader(open(f, newline=""))) for f in sys.argv[1:])
assert all(r["tolerance"] == "1e-06" and r["acceptance"] == "0.0001" for r in tol), tol
assert all(r["tolerance"] == "1e-12" and r["acceptance"] == "" and "profile_knots" not in r for r in default), default
assert all(r["acceptance"] == "1e-11" and r["profile_knots"] == "true" for r in knots), knots
PY
refused_resume() {  # FILE SWEEP EXPECTED OPTIONS...
  local file=$1 sweep=$2 expected=$3
  shift 3
  cp "$file" "$tmp/resume_before"
  "$rhabel" sweep "$sweep" --out "$file" "$@" > /dev/null 2> "$tmp/err"; rc=$?
  [ "$rc" -eq 2 ] && [ "$(wc -l < "$tmp/err")" -eq 1 ] && grep -qF -- "$expected" "$tmp/err" \
    || fail "resumed with $*: rc $rc, $(cat "$tmp/err")"
  cmp -s "$file" "$tmp/resume_before" || fail "a refused resume ($*) changed the file"
}
refused_resume "$tmp/tol.csv" "$tmp/two.json" \
  "line 2 was solved with tolerance 1e-06, acceptance 0.0001, this run asks tolerance 1e-06, acceptance 1e-05" \
  --tolerance 1e-6 --acceptance 1e-5
refused_resume "$tmp/tol.csv" "$tmp/two.json" "this run asks tolerance 1e-06, acceptance default" --tolerance 1e-6
refused_resume "$tmp/knots.csv" "$tmp/knots.json" \
  "solved with tolerance 1e-12, acceptance 1e-11, profile_knots true, this run asks tolerance 1e-12, acceptance 1e-11, profile_knots false" \
  --acceptance 1e-11
"$rhabel" sweep "$tmp/two.json" --out "$tmp/tol.jsonl" --jsonl --tolerance 1e-6 --acceptance 1e-4 2> /dev/null \
  || fail "--jsonl --tolerance 1e-6 --acceptance 1e-4: exit $?"
refused_resume "$tmp/tol.jsonl" "$tmp/two.json" "solved with tolerance 1e-06, acceptance 0.0001, this run asks tolerance 1e-07" \
  --jsonl --tolerance 1e-7 --acceptance 1e-4
cp "$tmp/tol.csv" "$tmp/tol_before.csv"
"$rhabel" sweep "$tmp/two.json" --out "$tmp/tol.csv" --tolerance 1e-6 --acceptance 1e-4 --time-limit 100 2> "$tmp/err" \
  || fail "resumed with another --time-limit: exit $? ($(cat "$tmp/err"))"
cmp -s "$tmp/tol.csv" "$tmp/tol_before.csv" || fail "resuming a complete sweep with another --time-limit changed it"
# A file whose rows do not record their options (written before they did) is refused by name,
# not taken for another sweep's (CSV) or for torn rows solved again (JSON lines).
sed '1s/,tolerance,acceptance,/,/' "$tmp/tol.csv" > "$tmp/old.csv"
sed 's/"tolerance":[^,]*,"acceptance":[^,]*,//' "$tmp/tol.jsonl" > "$tmp/old.jsonl"
{ head -1 "$tmp/old.csv" | grep -q tolerance || grep -q '"tolerance":' "$tmp/old.jsonl"; } &&
  fail "the option columns were not stripped from the old-format files"
refused_resume "$tmp/old.csv" "$tmp/two.json" "has no solve-option columns (tolerance, acceptance)" --tolerance 1e-6 --acceptance 1e-4
refused_resume "$tmp/old.jsonl" "$tmp/two.json" "line 1 has no solve-option columns" --jsonl --tolerance 1e-6 --acceptance 1e-4

for bad in "--tolerance nan" "--tolerance inf" "--tolerance 0" "--tolerance 1e-16" "--tolerance 0.1" "--tolerance abc" \
           "--acceptance nan" "--acceptance 0" "--acceptance 1" "--threads -1" "--threads 4097" "--threads x"; do
  # shellcheck disable=SC2086  # "OPTION VALUE" splits in two on purpose
  "$rhabel" sweep "$tmp/two.json" --out "$tmp/bad_option.csv" $bad > /dev/null 2> "$tmp/err"; rc=$?
  [ "$rc" -eq 2 ] && [ "$(wc -l < "$tmp/err")" -eq 1 ] && grep -q -- "${bad%% *}" "$tmp/err" && [ ! -e "$tmp/bad_option.csv" ] \
    || fail "$bad: rc $rc, $(cat "$tmp/err")"
done

# --- the shipped example runs ---------------------------------------------------------------------
"$rhabel" sweep "$src/examples/friction_speed_sweep.json" --out "$tmp/friction.csv" 2> "$tmp/err" \
  || fail "examples/friction_speed_sweep.json: exit $? ($(cat "$tmp/err"))"

[ "$failures" -eq 0 ] && echo "test_sweep: all checks passed"
exit $(( failures > 0 ))
