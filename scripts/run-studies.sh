#!/usr/bin/env bash
# Runs every study executable <build>/bin/study_* with its default arguments (`make studies`).
#
#   scripts/run-studies.sh [NAME_REGEX]
#
# Each study runs with <build>/studies/ as its working directory; its standard output (the CSV)
# goes to <build>/studies/<name>.csv and its standard error (progress, markdown summaries) to
# <build>/studies/<name>.log. A study that writes its own files into the working directory and
# nothing on standard output leaves no empty .csv behind. NAME_REGEX (an extended regular
# expression on <name>, the part after "study_") restricts the run. The build directory is
# `build` (the release preset) unless RHABEL_BUILD_DIR says otherwise.
# Exit status: 0 if every study succeeded, 1 otherwise (the others still run).
set -uo pipefail
cd "$(dirname "$0")/.." || exit 1

build_dir="$(cd "${RHABEL_BUILD_DIR:-build}" 2>/dev/null && pwd)" || {
  echo "run-studies: build directory '${RHABEL_BUILD_DIR:-build}' not found; build first (make build)" >&2
  exit 1
}
out_dir="$build_dir/studies"
mkdir -p "$out_dir"
filter="${1:-}"

shopt -s nullglob
executables=()
for exe in "$build_dir"/bin/study_*; do
  [[ -f "$exe" && -x "$exe" ]] || continue
  name="$(basename "$exe")"
  name="${name#study_}"
  if [[ -n "$filter" ]] && ! [[ "$name" =~ $filter ]]; then continue; fi
  executables+=("$exe")
done
if (( ${#executables[@]} == 0 )); then
  echo "run-studies: no study executables${filter:+ matching "$filter"} in $build_dir/bin" \
       "(configure with -DRHABEL_BUILD_STUDIES=ON and build)" >&2
  exit 1
fi

failed=()
for exe in "${executables[@]}"; do
  name="$(basename "$exe")"
  name="${name#study_}"
  printf 'study %-32s ' "$name"
  start=$SECONDS
  (cd "$out_dir" && "$exe") >"$out_dir/$name.csv" 2>"$out_dir/$name.log"
  status=$?
  [[ -s "$out_dir/$name.csv" ]] || rm -f "$out_dir/$name.csv"
  if (( status == 0 )); then
    echo "ok      $(( SECONDS - start )) s"
  else
    echo "FAILED  (exit $status after $(( SECONDS - start )) s; see $out_dir/$name.log)"
    failed+=("$name")
  fi
done

echo "results in $out_dir"
if (( ${#failed[@]} > 0 )); then
  echo "failed studies: ${failed[*]}" >&2
  exit 1
fi
