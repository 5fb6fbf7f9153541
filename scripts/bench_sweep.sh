#!/usr/bin/env bash
# Times `rhabel sweep` on the 10^4 single-wedge scenes of bench/sweep_wedges.json against
# rhabel::punch::solve alone on the same scenes (build/bin/bench_sweep_baseline), and the speed-up
# from 1 to 2 threads and from 1 to 2 MPI ranks (1 thread each). Wall and CPU seconds (CPU time is
# the steadier figure on a shared machine). Measures, asserts nothing.
# Needs: cmake --build build --target rhabel_cli bench_sweep_baseline (rhabel_cli with
# -DRHABEL_WITH_MPI=ON for the MPI lines). Usage: scripts/bench_sweep.sh
set -euo pipefail
cd "$(dirname "$0")/.."
rhabel=build/bin/rhabel
tmp="$(mktemp -d)"; trap 'rm -rf "$tmp"' EXIT
run() {  # run COMMAND...: prints "wall cpu" in seconds (children included)
  rm -f "$tmp/out.csv"
  /usr/bin/time -f "%e %U %S" -o "$tmp/time" "$@" > /dev/null 2>&1 || true
  awk '{printf "%s %.3f\n", $1, $2 + $3}' "$tmp/time"
}
read -r base base_cpu < <(build/bin/bench_sweep_baseline --benchmark_format=json 2> /dev/null |
  /usr/bin/python3 -c "import json,sys; b=json.load(sys.stdin)['benchmarks'][0]; print(b['real_time'], b['cpu_time'])")
read -r t1 c1 < <(run "$rhabel" sweep bench/sweep_wedges.json --out "$tmp/out.csv" --threads 1 --quiet)
read -r t2 c2 < <(run "$rhabel" sweep bench/sweep_wedges.json --out "$tmp/out.csv" --threads 2 --quiet)
r() { /usr/bin/python3 -c "print(f'{$1:.3f}')"; }
echo "punch::solve alone   wall $base s, cpu $base_cpu s ($(r "$base_cpu * 100") us per scene)"
echo "sweep, 1 thread      wall $t1 s, cpu $c1 s ($(r "$c1 * 100") us per scene; cpu $(r "$c1 / $base_cpu")x, wall $(r "$t1 / $base")x punch::solve alone)"
echo "sweep, 2 threads     wall $t2 s, cpu $c2 s (wall speed-up $(r "$t1 / $t2")x)"
if command -v mpirun > /dev/null && ldd "$rhabel" | grep -q libmpi; then
  read -r m1 mc1 < <(run mpirun --allow-run-as-root --oversubscribe -np 1 "$rhabel" sweep bench/sweep_wedges.json --out "$tmp/out.csv" --threads 1 --quiet)
  read -r m2 mc2 < <(run mpirun --allow-run-as-root --oversubscribe -np 2 "$rhabel" sweep bench/sweep_wedges.json --out "$tmp/out.csv" --threads 1 --quiet)
  echo "mpirun -np 1         wall $m1 s, cpu $mc1 s (incl. mpirun start-up)"
  echo "mpirun -np 2         wall $m2 s, cpu $mc2 s (wall speed-up $(r "$m1 / $m2")x)"
fi
uptime
