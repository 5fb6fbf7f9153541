#!/usr/bin/env bash
# Times `rhabel sweep` on the 10^4 single-wedge scenes of bench/sweep_wedges.json against
# rhabel::punch::solve alone on the same scenes (build/bin/bench_sweep_baseline), and the speed-up
# from 1 to 2 threads and from 1 to 2 MPI ranks (1 thread each). Measures, asserts nothing.
# Needs: cmake --build build --target rhabel_cli bench_sweep_baseline (rhabel_cli with
# -DRHABEL_WITH_MPI=ON for the MPI line). Usage: scripts/bench_sweep.sh
set -euo pipefail
cd "$(dirname "$0")/.."
rhabel=build/bin/rhabel
tmp="$(mktemp -d)"; trap 'rm -rf "$tmp"' EXIT
now() { date +%s.%N; }
run() {  # run COMMAND...: wall seconds
  rm -f "$tmp/out.csv"
  local t0; t0=$(now)
  "$@" > /dev/null 2>&1 || [ $? -eq 3 ]
  echo "$(now) - $t0" | bc -l
}
base=$(build/bin/bench_sweep_baseline --benchmark_format=json 2> /dev/null |
       /usr/bin/python3 -c "import json,sys; b=json.load(sys.stdin)['benchmarks'][0]; print(b['real_time'])")
t1=$(run "$rhabel" sweep bench/sweep_wedges.json --out "$tmp/out.csv" --threads 1 --quiet)
t2=$(run "$rhabel" sweep bench/sweep_wedges.json --out "$tmp/out.csv" --threads 2 --quiet)
printf 'punch::solve alone     %8.3f s  (%.1f us per scene)\n' "$base" "$(echo "$base * 100" | bc -l)"
printf 'sweep, 1 thread        %8.3f s  (%.1f us per scene, %.3fx punch::solve alone)\n' "$t1" "$(echo "$t1 * 100" | bc -l)" "$(echo "$t1 / $base" | bc -l)"
printf 'sweep, 2 threads       %8.3f s  (speed-up %.2fx)\n' "$t2" "$(echo "$t1 / $t2" | bc -l)"
if command -v mpirun > /dev/null && ldd "$rhabel" | grep -q libmpi; then
  m1=$(run mpirun --allow-run-as-root --oversubscribe -np 1 "$rhabel" sweep bench/sweep_wedges.json --out "$tmp/out.csv" --threads 1 --quiet)
  m2=$(run mpirun --allow-run-as-root --oversubscribe -np 2 "$rhabel" sweep bench/sweep_wedges.json --out "$tmp/out.csv" --threads 1 --quiet)
  printf 'mpirun -np 1           %8.3f s  (incl. mpirun start-up)\n' "$m1"
  printf 'mpirun -np 2           %8.3f s  (speed-up %.2fx)\n' "$m2" "$(echo "$m1 / $m2" | bc -l)"
fi
uptime
