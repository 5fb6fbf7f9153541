#!/usr/bin/env bash
# CLI test of `rhabel solve` on bad scenes:
#   bash test_solve_errors.sh <path-to-rhabel-binary> <source-dir>
# Every class of bad input must give exit code 2, exactly one line on stderr that names the
# field (as a path such as indentors[0].radius) and, for numbers, the valid range; nothing on
# stdout; and no CSV file (each case is run with --csv).
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
  "$rhabel" solve "$tmp/scene.json" --grid 5 --csv "$tmp/out" > "$tmp/stdout" 2> "$tmp/stderr"
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

# unreadable files
"$rhabel" solve "$tmp/does-not-exist.json" > "$tmp/stdout" 2> "$tmp/stderr"; rc=$?
[ "$rc" -eq 2 ] && [ ! -s "$tmp/stdout" ] && [ "$(wc -l < "$tmp/stderr")" -eq 1 ] && grep -q "does-not-exist.json" "$tmp/stderr" \
  || fail "missing file: rc $rc, $(cat "$tmp/stderr")"
"$rhabel" solve "$tmp" > "$tmp/stdout" 2> "$tmp/stderr"; rc=$?
[ "$rc" -eq 2 ] && [ ! -s "$tmp/stdout" ] && grep -q "directory" "$tmp/stderr" || fail "directory as scene: rc $rc, $(cat "$tmp/stderr")"
# bad options
"$rhabel" solve "$tmp/scene.json" --grid 1 > "$tmp/stdout" 2> "$tmp/stderr"; rc=$?
[ "$rc" -eq 2 ] && [ ! -s "$tmp/stdout" ] && grep -q -- "--grid" "$tmp/stderr" || fail "--grid 1: rc $rc, $(cat "$tmp/stderr")"
# unwritable CSV prefix: exit 2, nothing on stdout, no stray file
printf '%s' "{$M, \"speed\": 1, \"indentors\": [$P]}" > "$tmp/good.json"
"$rhabel" solve "$tmp/good.json" --csv "$tmp/no-such-dir/x" > "$tmp/stdout" 2> "$tmp/stderr"; rc=$?
[ "$rc" -eq 2 ] && [ ! -s "$tmp/stdout" ] && grep -q -- "--csv" "$tmp/stderr" || fail "unwritable --csv: rc $rc, $(cat "$tmp/stderr")"

# an empty --csv prefix is an error, not "no CSV"
"$rhabel" solve "$tmp/good.json" --csv "" > "$tmp/stdout" 2> "$tmp/stderr"; rc=$?
[ "$rc" -eq 2 ] && [ ! -s "$tmp/stdout" ] && grep -q -- "--csv" "$tmp/stderr" || fail "empty --csv: rc $rc, $(cat "$tmp/stderr")"

[ "$failures" -eq 0 ] && echo "test_solve_errors: all passed"
exit "$failures"
