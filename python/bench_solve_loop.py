#!/usr/bin/env python3
"""Benchmark (not a test): 1000 single-parabola scenes solved one after the other through
rhabel.solve from Python, against the same loop in C++ (bench/solve_loop.cpp,
build/bin/bench_solve_loop, run by this script when it is built).

    PYTHONPATH=build/python /usr/bin/python3 python/bench_solve_loop.py [--repeat 7] [--bench PATH]

Prints the minimum over interleaved repetitions of the loop's wall time, with the residual on (the default)
and off, the part spent inside punch::solve (sum of diagnostics.seconds) and, with the C++ figures,
the ratio Python / C++. The scenes: alpha = 0.3, E1 = 1e6, nu = 0.3, k = 0.5, U = 0.01,
R = 0.02, load 50 + 0.1 i N/m, i = 0 .. 999 (the same as bench/solve_loop.cpp).
"""

import argparse
import json
import pathlib
import subprocess
import sys
import time

# python/ (this script's directory, first on sys.path) holds the package's sources without the
# compiled extension: import the built one from PYTHONPATH instead.
sys.path = [p for p in sys.path if pathlib.Path(p or ".").resolve() != pathlib.Path(__file__).resolve().parent]
import rhabel  # noqa: E402

COUNT = 1000


def scenes():
    return [{"material": {"alpha": 0.3, "E1": 1.0e6, "nu": 0.3, "coulomb": 0.5}, "speed": 0.01,
             "indentors": [{"shape": "parabolic", "radius": 0.02, "load": 50.0 + 0.1 * i, "apex": 0.0}]}
            for i in range(COUNT)]


def python_loop(todo, residual):
    """Seconds of one loop, and the part spent inside punch::solve (sum of diagnostics.seconds)."""
    start = time.perf_counter()
    results = [rhabel.solve(s, residual=residual) for s in todo]
    elapsed = time.perf_counter() - start
    return elapsed, sum(r.diagnostics.seconds for r in results)


def cpp_loop(path):
    """Seconds of one loop of bench_solve_loop, keyed by the residual flag; None without the binary."""
    if not path.is_file():
        return None
    out = subprocess.run([str(path), "--benchmark_repetitions=1", "--benchmark_format=json"],
                         check=True, capture_output=True, text=True).stdout
    best = {}
    for b in json.loads(out)["benchmarks"]:
        if b.get("run_type") != "iteration":
            continue
        residual = b["name"].split("residual:")[1].split("/")[0] == "1"
        best[residual] = b["real_time"] * {"ms": 1e-3, "us": 1e-6, "ns": 1e-9, "s": 1.0}[b["time_unit"]]
    return best


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--repeat", type=int, default=7)
    default_bench = pathlib.Path(__file__).resolve().parents[1] / "build" / "bin" / "bench_solve_loop"
    parser.add_argument("--bench", type=pathlib.Path, default=default_bench)
    args = parser.parse_args()

    todo = scenes()
    rhabel.solve(todo[0])  # warm up (first touch of the module's code and tables)
    # Interleaved runs, minimum of each: the machine's load changes between runs.
    py = {True: (float("inf"), 0.0), False: (float("inf"), 0.0)}
    cpp = {True: float("inf"), False: float("inf")} if args.bench.is_file() else None
    for _ in range(args.repeat):
        if cpp is not None:
            for residual, seconds in cpp_loop(args.bench).items():
                cpp[residual] = min(cpp[residual], seconds)
        for residual in (True, False):
            py[residual] = min(py[residual], python_loop(todo, residual))
    print(f"{COUNT} single-parabola solves, minimum of {args.repeat} interleaved runs (rhabel {rhabel.__version__})")
    print(f"{'residual':>8} {'Python [s]':>11} {'inside solve [s]':>17} {'C++ [s]':>9} {'Python/C++':>11} "
          f"{'overhead/solve [us]':>20}")
    for residual in (True, False):
        seconds, inside = py[residual]
        c = cpp[residual] if cpp else float("nan")
        overhead = (seconds - (c if cpp else inside)) / COUNT * 1e6
        print(f"{str(residual):>8} {seconds:11.4f} {inside:17.4f} {c:9.4f} {seconds / c:11.3f} {overhead:20.1f}")
    if cpp is None:
        print(f"(no C++ figures: build {args.bench.name} with cmake --build build --target bench_solve_loop)")


if __name__ == "__main__":
    main()
