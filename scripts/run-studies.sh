#!/usr/bin/env bash
# Runs the study executables <build>/bin/study_* (`make studies`).
#
#   scripts/run-studies.sh [NAME_REGEX]     every study, default arguments, into <build>/studies/
#   scripts/run-studies.sh --record         the studies behind the committed results, into
#                                           studies/results/ (see studies/README.md)
#
# Each study runs with its output directory as its working directory; its standard output (the
# CSV) goes to <out>/<name>.csv and its standard error (progress, markdown summaries) to
# <out>/<name>.log. A study that writes its own files into the working directory and nothing on
# standard output leaves no empty .csv behind. NAME_REGEX (an extended regular expression on
# <name>, the part after "study_") restricts the run. The build directory is `build` (the release
# preset) unless RHABEL_BUILD_DIR says otherwise.
#
# --record runs the fixed list in RECORDED below, each with the arguments given there (the quick
# mode of the long ones), and writes studies/results/MACHINE.md: date, commit, machine, load
# average and the command of every study, with its wall time. notebooks/work_precision.ipynb
# plots these CSVs.
# Exit status: 0 if every study succeeded, 1 otherwise (the others still run).
set -uo pipefail
cd "$(dirname "$0")/.." || exit 1

build_dir="$(cd "${RHABEL_BUILD_DIR:-build}" 2>/dev/null && pwd)" || {
  echo "run-studies: build directory '${RHABEL_BUILD_DIR:-build}' not found; build first (make build)" >&2
  exit 1
}
# The committed results: name and arguments, default runs (about 16 min on two shared cores, 13 of
# them study_multi_contact's; its --quick run, ~25 s, has the usual BEM at one alpha only), and
# solve_union's two routes for nearly touching intervals side by side (union_convergence.csv).
RECORDED=(
  "quadrature_convergence"
  "gauss_jacobi_timing"
  "riemann_convergence"
  "multi_contact"
  "union_convergence - 1024 layered"
)

record=0
filter=""
case "${1:-}" in
  --record) record=1 ;;
  -h|--help) sed -n '2,20p' "$0"; exit 0 ;;
  *) filter="${1:-}" ;;
esac

runs=()   # "name args..."
if (( record )); then
  out_dir="$PWD/studies/results"
  runs=("${RECORDED[@]}")
else
  out_dir="$build_dir/studies"
  shopt -s nullglob
  for exe in "$build_dir"/bin/study_*; do
    [[ -f "$exe" && -x "$exe" ]] || continue
    name="$(basename "$exe")"
    name="${name#study_}"
    if [[ -n "$filter" ]] && ! [[ "$name" =~ $filter ]]; then continue; fi
    runs+=("$name")
  done
fi
mkdir -p "$out_dir"
if (( ${#runs[@]} == 0 )); then
  echo "run-studies: no study executables${filter:+ matching "$filter"} in $build_dir/bin" \
       "(configure with -DRHABEL_BUILD_STUDIES=ON and build)" >&2
  exit 1
fi
for run in "${runs[@]}"; do
  exe="$build_dir/bin/study_${run%% *}"
  if ! [[ -x "$exe" ]]; then
    echo "run-studies: $exe is not built (cmake --build $build_dir --target study_${run%% *})" >&2
    exit 1
  fi
done

if (( record )); then
  {
    echo "# Machine and commands of the committed study results"
    echo
    echo "Written by \`scripts/run-studies.sh --record\` (from the source directory, Release build in"
    echo "\`${RHABEL_BUILD_DIR:-build}\`); every CSV here is the standard output of the command beside it, run in"
    echo "this directory, and the .log its standard error."
    echo
    echo "- date: $(date -u '+%Y-%m-%d %H:%M UTC')"
    echo "- commit: $(git rev-parse --short HEAD 2>/dev/null || echo unknown)$(git diff --quiet HEAD -- 2>/dev/null || echo ' (with uncommitted changes)')"
    echo "- machine: $(grep -m1 'model name' /proc/cpuinfo 2>/dev/null | sed 's/.*: //'), $(nproc) hardware threads, $(uname -sr)"
    echo "- load average (1, 5, 15 min) at the start: $(cut -d' ' -f1-3 /proc/loadavg)"
    echo
    echo "| study | command | wall time |"
    echo "| --- | --- | ---: |"
  } >"$out_dir/MACHINE.md"
fi

failed=()
for run in "${runs[@]}"; do
  name="${run%% *}"
  args=()
  [[ "$run" == *" "* ]] && read -r -a args <<<"${run#* }"
  exe="$build_dir/bin/study_$name"
  printf 'study %-32s ' "$name"
  start=$SECONDS
  (cd "$out_dir" && "$exe" "${args[@]}") >"$out_dir/$name.csv" 2>"$out_dir/$name.log"
  status=$?
  [[ -s "$out_dir/$name.csv" ]] || rm -f "$out_dir/$name.csv"
  if (( status == 0 )); then
    echo "ok      $(( SECONDS - start )) s"
  else
    echo "FAILED  (exit $status after $(( SECONDS - start )) s; see $out_dir/$name.log)"
    failed+=("$name")
  fi
  if (( record )); then
    echo "| \`$name\` | \`study_$run > $name.csv 2> $name.log\` | $(( SECONDS - start )) s |" >>"$out_dir/MACHINE.md"
  fi
done

echo "results in $out_dir"
if (( ${#failed[@]} > 0 )); then
  echo "failed studies: ${failed[*]}" >&2
  exit 1
fi
