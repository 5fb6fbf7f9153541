#!/usr/bin/env bash
# CLI test of `rhabel solve` on bad scenes:
#   bash test_solve_errors.sh <path-to-rhabel-binary> <source-dir>
# Every class of bad input must give exit code 2, exactly one line on stderr that names the
# field (as a path such as indentors[0].radius) and, for numbers, the valid range; nothing on
# stdout; and no CSV file (each case is run with --csv). Issue 14: a NUL byte, trailing bytes,
# nesting beyond 256 levels (up to 10^6, which crashed), arguments holding newlines, and a failed
# write to stdout (/dev/full, a closed descriptor: exit code 2, one line, no CSV file left).
set -u
rhabel="$1"
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }
tmp="$(mktemp -d)"; trap 'rm -rf "$tmp"' EXIT

M='"material": {"alpha": 0.3, "E1": 1.0e6, "nu": 0.5, "coulomb": 0.0}'
P='{"shape": "parabolic", "radius": 0.02, "load": 100.0}'

# expect_bad NAME SCENE-TEXT WORD...: every WORD must appear in the message.
expect_bad() {
  local name="$1" scene="$2"; shift 2
  printf '%s' "$scene" > "$tmp/scene.json"
  expect_bad_file "$name" "$tmp/scene.json" "$@"
}

# expect_bad_file NAME FILE WORD...: the same for a scene already in FILE (bytes a shell
# variable cannot hold, such as NUL).
expect_bad_file() {
  local name="$1" file="$2"; shift 2
  "$rhabel" solve "$file" --grid 5 --csv "$tmp/out" > "$tmp/stdout" 2> "$tmp/stderr"
  local rc=$?
  [ "$rc" -eq 2 ] || fail "$name: exit code $rc, expected 2"
  [ -s "$tmp/stdout" ] && fail "$name: partial output on stdout"
  ls "$tmp"/out* > /dev/null 2>&1 && { fail "$name: CSV written"; rm -f "$tmp"/out*; }
  [ "$(wc -l < "$tmp/stderr")" -eq 1 ] || fail "$name: stderr is not one line: $(cat "$tmp/stderr")"
  for word in "$@"; do
    grep -q -F -- "$word" "$tmp/stderr" || fail "$name: message lacks '$word': $(cat "$tmp/stderr")"
  done
}

# malformed JSON and wrong top level
expect_bad malformed_json '{"material": {' "not valid JSON"
expect_bad trailing_comma "{$M, \"speed\": 1, \"indentors\": [$P],}" "not valid JSON"
expect_bad trailing_garbage "{$M, \"speed\": 1, \"indentors\": [$P]} x" "not valid JSON"
expect_bad empty_input '' "not valid JSON"
expect_bad top_level_array "[$P]" "top level" "object"
# missing fields
expect_bad missing_material "{\"speed\": 1, \"indentors\": [$P]}" "material" "missing"
expect_bad missing_speed "{$M, \"indentors\": [$P]}" "speed" "missing" "(0, inf)"
expect_bad missing_alpha '{"material": {"E1": 1, "nu": 0.5, "coulomb": 0}, "speed": 1, "indentors": [{"shape": "flat", "width": 1, "load": 1}]}' "material.alpha" "missing" "[0, 1)"
expect_bad missing_radius "{$M, \"speed\": 1, \"indentors\": [{\"shape\": \"parabolic\", \"load\": 1}]}" "indentors[0].radius" "missing"
expect_bad missing_slope "{$M, \"speed\": 1, \"indentors\": [$P, {\"shape\": \"wedge\", \"slope_leading\": 0.1, \"load\": 1}]}" "indentors[1].slope_trailing" "missing"
expect_bad missing_shape "{$M, \"speed\": 1, \"indentors\": [{\"radius\": 1, \"load\": 1}]}" "indentors[0].shape" "missing"
expect_bad missing_indentors "{$M, \"speed\": 1}" "indentors" "missing"
# unknown fields, including a field of another shape
expect_bad unknown_top "{$M, \"speed\": 1, \"indentors\": [$P], \"sped\": 2}" "sped" "not a known field"
expect_bad unknown_material '{"material": {"alpha": 0.3, "E1": 1, "nu": 0.5, "coulomb": 0, "E2": 3}, "speed": 1, "indentors": [{"shape": "flat", "width": 1, "load": 1}]}' "material.E2" "not a known field"
expect_bad radius_on_wedge "{$M, \"speed\": 1, \"indentors\": [{\"shape\": \"wedge\", \"slope_leading\": 0.1, \"slope_trailing\": 0.1, \"radius\": 1, \"load\": 1}]}" "indentors[0].radius" "not a known field" "wedge"
expect_bad unknown_shape "{$M, \"speed\": 1, \"indentors\": [{\"shape\": \"cone\", \"load\": 1}]}" "indentors[0].shape" "cone" "parabolic"
# ranges
expect_bad alpha_one '{"material": {"alpha": 1, "E1": 1, "nu": 0.5, "coulomb": 0}, "speed": 1, "indentors": [{"shape": "flat", "width": 1, "load": 1}]}' "material.alpha" "[0, 1)"
expect_bad alpha_negative '{"material": {"alpha": -0.1, "E1": 1, "nu": 0.5, "coulomb": 0}, "speed": 1, "indentors": [{"shape": "flat", "width": 1, "load": 1}]}' "material.alpha" "[0, 1)"
expect_bad nu_above_half '{"material": {"alpha": 0.1, "E1": 1, "nu": 0.6, "coulomb": 0}, "speed": 1, "indentors": [{"shape": "flat", "width": 1, "load": 1}]}' "material.nu" "[0, 0.5]"
expect_bad E1_zero '{"material": {"alpha": 0.1, "E1": 0, "nu": 0.5, "coulomb": 0}, "speed": 1, "indentors": [{"shape": "flat", "width": 1, "load": 1}]}' "material.E1" "(0, inf)"
expect_bad coulomb_negative '{"material": {"alpha": 0.1, "E1": 1, "nu": 0.3, "coulomb": -0.2}, "speed": 1, "indentors": [{"shape": "flat", "width": 1, "load": 1}]}' "material.coulomb" "[0, inf)"
expect_bad speed_zero "{$M, \"speed\": 0, \"indentors\": [$P]}" "speed" "(0, inf)"
expect_bad load_zero "{$M, \"speed\": 1, \"indentors\": [{\"shape\": \"parabolic\", \"radius\": 1, \"load\": 0}]}" "indentors[0].load" "(0, inf)"
expect_bad load_negative "{$M, \"speed\": 1, \"indentors\": [$P, {\"shape\": \"flat\", \"width\": 1, \"load\": -5}]}" "indentors[1].load" "(0, inf)"
expect_bad radius_negative "{$M, \"speed\": 1, \"indentors\": [{\"shape\": \"parabolic\", \"radius\": -0.02, \"load\": 1}]}" "indentors[0].radius" "(0, inf)"
expect_bad width_zero "{$M, \"speed\": 1, \"indentors\": [{\"shape\": \"flat\", \"width\": 0, \"load\": 1}]}" "indentors[0].width" "(0, inf)"
expect_bad slope_negative "{$M, \"speed\": 1, \"indentors\": [{\"shape\": \"wedge\", \"slope_leading\": -0.1, \"slope_trailing\": 0.1, \"load\": 1}]}" "indentors[0].slope_leading" "(0, inf)"
# non-finite numbers (JSON has no NaN literal; 1e400 overflows a double)
expect_bad overflow "{$M, \"speed\": 1, \"indentors\": [{\"shape\": \"parabolic\", \"radius\": 1e400, \"load\": 1}]}" "indentors[0].radius" "1e400"
expect_bad nan_literal "{$M, \"speed\": NaN, \"indentors\": [$P]}" "not valid JSON"
expect_bad underflow_to_zero "{$M, \"speed\": 1, \"indentors\": [{\"shape\": \"parabolic\", \"radius\": 1e-400, \"load\": 1}]}" "indentors[0].radius" "(0, inf)"
# wrong types
expect_bad speed_string "{$M, \"speed\": \"0.01\", \"indentors\": [$P]}" "speed" "a string"
expect_bad load_boolean "{$M, \"speed\": 1, \"indentors\": [{\"shape\": \"parabolic\", \"radius\": 1, \"load\": true}]}" "indentors[0].load" "a boolean"
expect_bad apex_null "{$M, \"speed\": 1, \"indentors\": [{\"shape\": \"parabolic\", \"radius\": 1, \"load\": 1, \"apex\": null}]}" "indentors[0].apex" "null"
expect_bad material_array "{\"material\": [], \"speed\": 1, \"indentors\": [$P]}" "material" "object"
expect_bad indentors_object "{$M, \"speed\": 1, \"indentors\": $P}" "indentors" "array"
expect_bad indentor_number "{$M, \"speed\": 1, \"indentors\": [$P, 3]}" "indentors[1]" "object"
expect_bad shape_number "{$M, \"speed\": 1, \"indentors\": [{\"shape\": 1, \"radius\": 1, \"load\": 1}]}" "indentors[0].shape"
expect_bad name_number "{$M, \"speed\": 1, \"indentors\": [{\"shape\": \"parabolic\", \"radius\": 1, \"load\": 1, \"name\": 7}]}" "indentors[0].name" "string"
# empty list
expect_bad empty_indentors "{$M, \"speed\": 1, \"indentors\": []}" "indentors" "empty"
# duplicate keys (nlohmann-json would keep the last silently)
expect_bad duplicate_top "{$M, \"speed\": 1, \"speed\": 2, \"indentors\": [$P]}" "speed" "twice"
expect_bad duplicate_nested "{$M, \"speed\": 1, \"indentors\": [$P, {\"shape\": \"flat\", \"width\": 1, \"load\": 1, \"width\": 2}]}" "indentors[1].width" "twice"
# a message stays on one line even when the input has newlines near the error
expect_bad newline_in_error $'{"material":\n{\n"alpha": 0.3,\n"E1": x\n}}' "not valid JSON"

printf '%s' "{$M, \"speed\": 1, \"indentors\": [$P]}" > "$tmp/good.json"

# --- issue 14: the whole input is parsed; a NUL byte or trailing bytes name their byte offset --
good="{$M, \"speed\": 1, \"indentors\": [$P]}"
# "SCENE\0 garbage {{{" was accepted as SCENE: nlohmann-json takes a NUL for the end of input.
{ printf '%s' "$good"; printf '\0 garbage {{{'; } > "$tmp/nul.json"
expect_bad_file nul_after_scene "$tmp/nul.json" "NUL byte" "byte offset ${#good}"
{ printf '%s' "$good"; printf '\0'; } > "$tmp/nul.json"
expect_bad_file nul_at_end "$tmp/nul.json" "NUL byte" "byte offset ${#good}"
{ printf '{"desc\0ription": 1}'; } > "$tmp/nul.json"
expect_bad_file nul_in_string "$tmp/nul.json" "NUL byte" "byte offset 6"
expect_bad trailing_bytes_offset "$good x" "not valid JSON" "byte offset $((${#good} + 1))"
expect_bad second_object "$good$good" "not valid JSON" "byte offset ${#good}"

# --- issue 14: nesting depth. 75,000 levels crashed the program (stack overflow, SIGSEGV) ----
nest() { printf '%*s' "$1" '' | tr ' ' "$2"; }  # $1 copies of the character $2
for depth in 100000 1000000; do
  { printf '{"description": '; nest "$depth" '['; nest "$depth" ']'; printf '}'; } > "$tmp/deep.json"
  expect_bad_file "nested_${depth}_in_description" "$tmp/deep.json" "deeper than the limit of 256 levels" "byte offset 271"
  nest "$depth" '{' > "$tmp/deep.json"  # unterminated objects: refused before parsing
  expect_bad_file "nested_${depth}_objects_unterminated" "$tmp/deep.json" "deeper than the limit of 256" "byte offset 256"
done
# the same on stdin
{ printf '{"description": '; nest 100000 '['; nest 100000 ']'; printf '}'; } |
  "$rhabel" solve - > "$tmp/stdout" 2> "$tmp/stderr"; rc=$?
[ "$rc" -eq 2 ] && [ ! -s "$tmp/stdout" ] && [ "$(wc -l < "$tmp/stderr")" -eq 1 ] && grep -q "(stdin) nests" "$tmp/stderr" ||
  fail "nested 100000 on stdin: rc $rc, $(head -c 300 "$tmp/stderr")"
# The limit counts levels (the top-level object is level 1): 256 passes the scan (and is then
# judged by the schema), 257 does not. Brackets inside strings do not count.
expect_bad depth_256_passes_the_scan "{\"description\": $(nest 255 '[')$(nest 255 ']')}" "description must be a string"
expect_bad depth_257_refused "{\"description\": $(nest 256 '[')$(nest 256 ']')}" "deeper than the limit of 256" "byte offset 271"
expect_bad brackets_in_strings_do_not_count "{\"description\": \"$(nest 1000 '[')\\\"$(nest 1000 '{')\", \"x\": 1}" "x" "not a known field"

# --- issue 14: one-line messages also when an argument holds a newline -----------------------
expect_one_line() {
  local name="$1"; shift
  "$rhabel" "$@" > "$tmp/stdout" 2> "$tmp/stderr"; local rc=$?
  [ "$rc" -eq 2 ] || fail "$name: exit code $rc, expected 2"
  [ -s "$tmp/stdout" ] && fail "$name: output on stdout"
  [ "$(wc -l < "$tmp/stderr")" -eq 1 ] || fail "$name: stderr is not one line: $(cat "$tmp/stderr")"
  grep -q '^rhabel: solve: ' "$tmp/stderr" || fail "$name: message does not name the command: $(cat "$tmp/stderr")"
}
expect_one_line newline_in_scene_path solve $'no-such\nscene.json'
expect_one_line newline_in_grid solve "$tmp/scene.json" --grid $'4\n5'
expect_one_line newline_in_csv_prefix solve "$tmp/good.json" --csv "$tmp/no-such-dir/a"$'\n'"b"
expect_one_line carriage_return_and_escape solve $'x\r\x1b[2Jy.json'
grep -q -F 'x\r\x1b[2Jy.json' "$tmp/stderr" || fail "control characters not shown escaped: $(cat "$tmp/stderr")"
expect_one_line newline_in_option_name solve "$tmp/scene.json" $'--gr\nid' 4

# --- issue 14: a failed write to stdout is exit code 2 with one line, and leaves no CSV file --
# (it exited 1 with an empty stderr and left both CSV files on disk)
expect_write_error() {
  local name="$1"; shift
  rm -f "$tmp"/w_*
  sh -c "$1" "$rhabel" "$tmp" 2> "$tmp/stderr"; local rc=$?  # $0 = rhabel, $1 = tmp
  [ "$rc" -eq 2 ] || fail "$name: exit code $rc, expected 2"
  [ "$(wc -l < "$tmp/stderr")" -eq 1 ] || fail "$name: stderr is not one line: $(cat "$tmp/stderr")"
  grep -q '^rhabel: solve: cannot write the result to stdout' "$tmp/stderr" || fail "$name: message: $(cat "$tmp/stderr")"
  ls "$tmp"/w_* > /dev/null 2>&1 && fail "$name: files left behind: $(ls "$tmp"/w_*)"
}
if [ -w /dev/full ]; then
  expect_write_error full_device '"$0" solve "$1/good.json" --csv "$1/w_run" > /dev/full'
  expect_write_error full_device_grid '"$0" solve "$1/good.json" --grid 1000 --compact --csv "$1/w_run" > /dev/full'
  expect_write_error full_device_no_csv '"$0" solve "$1/good.json" > /dev/full'
fi
expect_write_error closed_stdout '"$0" solve "$1/good.json" --csv "$1/w_run" >&-'
# An existing CSV file is kept as it was when the run fails, and replaced when it succeeds.
printf 'old\n' > "$tmp/keep_pressure.csv"
if [ -w /dev/full ]; then
  "$rhabel" solve "$tmp/good.json" --csv "$tmp/keep" > /dev/full 2> /dev/null
  [ "$(cat "$tmp/keep_pressure.csv")" = old ] || fail "a failed run changed an existing CSV file"
  [ -e "$tmp/keep_displacement.csv" ] && fail "a failed run created keep_displacement.csv"
fi
"$rhabel" solve "$tmp/good.json" --csv "$tmp/keep" > /dev/null 2> "$tmp/stderr" || fail "csv run: $(cat "$tmp/stderr")"
head -n 1 "$tmp/keep_pressure.csv" | grep -q '^indentor,x,pressure$' || fail "the CSV file was not replaced"
[ "$(ls "$tmp" | grep -c 'keep_.*\.csv\.')" -eq 0 ] || fail "temporary files left: $(ls "$tmp")"

# --- issue 14: extreme valid scenes solve, or exit 2 naming the scene fields (never exit 1 or an
# internal parameter such as "abel_operator: lo = nan", "beta = 1", "no bracket"); the limits are
# in examples/README.md. Each of these gave exit 1 or an internal parameter's name.
W='{"shape": "wedge", "slope_leading": 0.02, "slope_trailing": 0.03'
expect_bad extreme_E1 '{"material": {"alpha": 0.3, "E1": 1e-300, "nu": 0.5, "coulomb": 0}, "speed": 0.01, "indentors": [{"shape": "parabolic", "radius": 0.01, "load": 100}]}' "material.E1" "effective modulus" "1e-250"
expect_bad extreme_coulomb '{"material": {"alpha": 0.3, "E1": 1e6, "nu": 0.3, "coulomb": 1e300}, "speed": 0.01, "indentors": [{"shape": "parabolic", "radius": 0.01, "load": 100}]}' "material.coulomb" "1e12"
expect_bad extreme_wedge_alpha '{"material": {"alpha": 0.999, "E1": 1e6, "nu": 0.5, "coulomb": 0}, "speed": 0.01, "indentors": ['"$W"', "load": 100}]}' "indentors[0].load" "indentors[0].slope_leading" "contact length" "1e-100"
expect_bad extreme_load '{"material": {"alpha": 0.3, "E1": 1e6, "nu": 0.5, "coulomb": 0}, "speed": 0.01, "indentors": [{"shape": "parabolic", "radius": 0.01, "load": 1.797e308}]}' "indentors[0].load" "indentors[0].radius" "contact length"
expect_bad extreme_elastic_load '{"material": {"alpha": 0, "E1": 1e6, "nu": 0.5, "coulomb": 0}, "speed": 0.01, "indentors": [{"shape": "parabolic", "radius": 0.01, "load": 1e300}]}' "indentors[0].load" "contact length"
expect_bad extreme_radius '{"material": {"alpha": 0.3, "E1": 1e6, "nu": 0.5, "coulomb": 0}, "speed": 0.01, "indentors": [{"shape": "parabolic", "radius": 1e300, "load": 100}]}' "indentors[0].radius" "contact length"
expect_bad extreme_width '{"material": {"alpha": 0.3, "E1": 1e6, "nu": 0.5, "coulomb": 0}, "speed": 0.01, "indentors": [{"shape": "flat", "width": 1e-320, "load": 100}]}' "indentors[0].width" "contact length"
expect_bad extreme_flat_load '{"material": {"alpha": 0.3, "E1": 1e6, "nu": 0.5, "coulomb": 0}, "speed": 0.01, "indentors": [{"shape": "flat", "width": 0.01, "load": 2e302}]}' "indentors[0].load" "indentors[0].width" "strain"
expect_bad extreme_slope_ratio '{"material": {"alpha": 0.3, "E1": 1e6, "nu": 0.5, "coulomb": 0}, "speed": 0.01, "indentors": [{"shape": "wedge", "slope_leading": 1e6, "slope_trailing": 0.01, "load": 100}]}' "indentors[0].slope_leading / indentors[0].slope_trailing" "1e+07"

# expect_solved NAME SCENE-TEXT STATUS ARGS...: exit 0 (STATUS ok) or 3, a JSON result with that
# status, nothing on stderr.
expect_solved() {
  local name="$1" scene="$2" status="$3"; shift 3
  printf '%s' "$scene" > "$tmp/scene.json"
  "$rhabel" solve "$tmp/scene.json" "$@" > "$tmp/stdout" 2> "$tmp/stderr"; local rc=$?
  local want=3; [ "$status" = ok ] && want=0
  [ "$rc" -eq "$want" ] || fail "$name: exit code $rc, expected $want: $(cat "$tmp/stderr")"
  [ -s "$tmp/stderr" ] && fail "$name: stderr: $(cat "$tmp/stderr")"
  /usr/bin/python3 -c 'import json, sys; d = json.load(open(sys.argv[1])); assert d["diagnostics"]["status"] == sys.argv[2], d["diagnostics"]' \
    "$tmp/stdout" "$status" 2> /dev/null || fail "$name: status is not $status"
}
# alpha + beta/2 - 1/2 = 1e-7: the displacement's Gauss-Jacobi rule (exponent -1e-7) failed
expect_solved near_boundary_grid '{"material": {"alpha": 0.5000001, "E1": 1e6, "nu": 0.5, "coulomb": 0}, "speed": 0.01, "indentors": [{"shape": "parabolic", "radius": 0.01, "load": 100}]}' ok --grid 100
expect_solved apex_1e15_grid '{"material": {"alpha": 0.3, "E1": 1e6, "nu": 0.5, "coulomb": 0}, "speed": 0.01, "indentors": [{"shape": "parabolic", "radius": 0.01, "load": 100, "apex": 1e15}]}' ok --grid 100
# alpha = 0.999 with a load that gives a contact of ~0.5 (int g = K L^(1 - alpha))
expect_solved wedge_alpha_0999 '{"material": {"alpha": 0.999, "E1": 1e6, "nu": 0.5, "coulomb": 0}, "speed": 1, "indentors": ['"$W"', "load": 4.18e4}]}' ok --grid 50
expect_solved leading_slope_ratio_1e7 '{"material": {"alpha": 0.3, "E1": 1e6, "nu": 0.5, "coulomb": 0}, "speed": 0.01, "indentors": [{"shape": "wedge", "slope_leading": 1e7, "slope_trailing": 1, "load": 1e13}]}' ok --grid 50
expect_solved leading_slope_ratio_above '{"material": {"alpha": 0.7, "E1": 1e6, "nu": 0.5, "coulomb": 0}, "speed": 0.01, "indentors": [{"shape": "wedge", "slope_leading": 1e15, "slope_trailing": 1, "load": 1e21}]}' ok --grid 50
expect_solved trailing_slope_ratio '{"material": {"alpha": 0.3, "E1": 1e6, "nu": 0.5, "coulomb": 0}, "speed": 0.01, "indentors": [{"shape": "wedge", "slope_leading": 0.01, "slope_trailing": 1e6, "load": 100}]}' ok --grid 50

# --- issue 14: fields cheap per sample. The solve's own clock (diagnostics.seconds: the solve and
# the sampling, not the JSON) with 10^5 samples of each field against without: a quadrature per
# displacement sample made this ratio ~70 (66-90 s for 10^6 samples of this ~0.1 s scene); sampling
# from interpolants makes it ~3, in Release and under ASan alike (both sides slow down together).
"$rhabel" solve "$2/examples/default_scene.json" --compact > "$tmp/plain.json" 2> "$tmp/stderr" || fail "default scene: $(cat "$tmp/stderr")"
"$rhabel" solve "$2/examples/default_scene.json" --grid 100000 --compact > "$tmp/grid.json" 2> "$tmp/stderr" || fail "default scene --grid 100000: $(cat "$tmp/stderr")"
/usr/bin/python3 - "$tmp/plain.json" "$tmp/grid.json" <<'PY' || fail "--grid 100000 costs more than 20 solves of the scene"
import json, sys
plain, grid = (json.load(open(f))["diagnostics"]["seconds"] for f in sys.argv[1:3])
print(f"default scene: solve {plain:.3f} s, with 10^5 samples {grid:.3f} s")
assert grid < 20 * plain + 0.05, (plain, grid)
PY
rm -f "$tmp/plain.json" "$tmp/grid.json"

# --- the exit codes are documented in --help ---------------------------------------------------
"$rhabel" solve --help > "$tmp/help" || fail "solve --help: exit code $?"
for line in "^Exit codes:" "^  0  ok" "^  1  internal error" "^  2  bad input, a scene that cannot be solved, or an output that could not be written"; do
  grep -q "$line" "$tmp/help" || fail "solve --help does not document the exit codes ($line)"
done

# unreadable files
"$rhabel" solve "$tmp/does-not-exist.json" > "$tmp/stdout" 2> "$tmp/stderr"; rc=$?
[ "$rc" -eq 2 ] && [ ! -s "$tmp/stdout" ] && [ "$(wc -l < "$tmp/stderr")" -eq 1 ] && grep -q "does-not-exist.json" "$tmp/stderr" \
  || fail "missing file: rc $rc, $(cat "$tmp/stderr")"
"$rhabel" solve "$tmp" > "$tmp/stdout" 2> "$tmp/stderr"; rc=$?
[ "$rc" -eq 2 ] && [ ! -s "$tmp/stdout" ] && grep -q "directory" "$tmp/stderr" || fail "directory as scene: rc $rc, $(cat "$tmp/stderr")"
# bad options
"$rhabel" solve "$tmp/scene.json" --grid 1 > "$tmp/stdout" 2> "$tmp/stderr"; rc=$?
[ "$rc" -eq 2 ] && [ ! -s "$tmp/stdout" ] && grep -q -- "--grid" "$tmp/stderr" || fail "--grid 1: rc $rc, $(cat "$tmp/stderr")"
for limit in -1 nan inf; do
  "$rhabel" solve "$tmp/good.json" --time-limit "$limit" > "$tmp/stdout" 2> "$tmp/stderr"; rc=$?
  [ "$rc" -eq 2 ] && [ ! -s "$tmp/stdout" ] && grep -q -- "--time-limit" "$tmp/stderr" \
    || fail "--time-limit $limit: rc $rc, $(cat "$tmp/stderr")"
done
for tolerance in nan inf -1 0 1e-16 0.1 abc ""; do
  "$rhabel" solve "$tmp/good.json" --tolerance "$tolerance" > "$tmp/stdout" 2> "$tmp/stderr"; rc=$?
  [ "$rc" -eq 2 ] && [ ! -s "$tmp/stdout" ] && [ "$(wc -l < "$tmp/stderr")" -eq 1 ] && grep -q -- "--tolerance" "$tmp/stderr" \
    || fail "--tolerance '$tolerance': rc $rc, $(cat "$tmp/stderr")"
done
for acceptance in nan 1 0 abc; do
  "$rhabel" solve "$tmp/good.json" --acceptance "$acceptance" > "$tmp/stdout" 2> "$tmp/stderr"; rc=$?
  [ "$rc" -eq 2 ] && [ ! -s "$tmp/stdout" ] && grep -q -- "--acceptance" "$tmp/stderr" \
    || fail "--acceptance $acceptance: rc $rc, $(cat "$tmp/stderr")"
done
# unwritable CSV prefix: exit 2, nothing on stdout, no stray file
"$rhabel" solve "$tmp/good.json" --csv "$tmp/no-such-dir/x" > "$tmp/stdout" 2> "$tmp/stderr"; rc=$?
[ "$rc" -eq 2 ] && [ ! -s "$tmp/stdout" ] && grep -q -- "--csv" "$tmp/stderr" || fail "unwritable --csv: rc $rc, $(cat "$tmp/stderr")"

# an empty --csv prefix is an error, not "no CSV"
"$rhabel" solve "$tmp/good.json" --csv "" > "$tmp/stdout" 2> "$tmp/stderr"; rc=$?
[ "$rc" -eq 2 ] && [ ! -s "$tmp/stdout" ] && grep -q -- "--csv" "$tmp/stderr" || fail "empty --csv: rc $rc, $(cat "$tmp/stderr")"

# --grid-spacing takes uniform or graded only
"$rhabel" solve "$tmp/good.json" --grid 5 --grid-spacing chebyshev > "$tmp/stdout" 2> "$tmp/stderr"; rc=$?
[ "$rc" -eq 2 ] && [ ! -s "$tmp/stdout" ] && grep -q -- "--grid-spacing" "$tmp/stderr" \
  || fail "--grid-spacing chebyshev: rc $rc, $(cat "$tmp/stderr")"

[ "$failures" -eq 0 ] && echo "test_solve_errors: all passed"
exit "$failures"
