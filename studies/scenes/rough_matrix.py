#!/usr/bin/env python3
"""Runs `rhabel solve` (the spectral contact search) on self-affine profiles, finite windows or
(--periodic) periodic, and prints one line a scene: samples, seed, load, status, contacts, load
fraction reached, wall time, the body's C_f, and the search's rounds (coupled solves of a contact
set) and Newton iterations in all.

    python3 studies/scenes/rough_matrix.py [--rhabel build/bin/rhabel] [--samples 1000 4000 16000]
        [--seeds 1 2 3] [--loads 5e-4 1e-3 2e-3 3e-3] [--acceptance 1e-6] [--time-limit 60] [--periodic]

Each scene is self_affine_profile.py N SEED LOAD (Hurst 0.8, rms 1e-3, alpha 0.3) solved with
--threads 1. A scene whose contacts would reach an end of its samples is refused by rhabel (exit
code 2); it is listed as "refused". With --periodic the samples are one period (profile.period 1,
profile.solver "spectral"): nothing is refused for reaching an end. The status of a solve that is not ok is its first 80
characters (docs: README, "Known limits").
"""
import argparse
import json
import os
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--rhabel", default=os.path.join(HERE, "..", "..", "build", "bin", "rhabel"))
    ap.add_argument("--samples", type=int, nargs="+", default=[1000, 4000, 16000])
    ap.add_argument("--seeds", type=int, nargs="+", default=[1, 2, 3])
    ap.add_argument("--loads", type=float, nargs="+", default=[5e-4, 1e-3, 2e-3, 3e-3])
    ap.add_argument("--acceptance", type=float, default=1e-6)
    ap.add_argument("--time-limit", type=float, default=60)
    ap.add_argument("--periodic", action="store_true")
    a = ap.parse_args()
    print(f"{'samples':>7} {'seed':>4} {'load':>7} {'status':<14} {'contacts':>8} {'fraction':>8} {'seconds':>8} "
          f"{'C_f':>14} {'rounds':>6} {'iters':>5}")
    for n in a.samples:
        for seed in a.seeds:
            for load in a.loads:
                scene = subprocess.run([sys.executable, os.path.join(HERE, "self_affine_profile.py"), str(n), str(seed),
                                        repr(load)] + (["--periodic"] if a.periodic else []),
                                       check=True, capture_output=True, text=True).stdout
                if a.periodic:
                    document = json.loads(scene)
                    document["profile"]["solver"] = "spectral"
                    scene = json.dumps(document)
                start = time.perf_counter()
                r = subprocess.run([a.rhabel, "solve", "-", "--acceptance", repr(a.acceptance), "--threads", "1",
                                    "--time-limit", repr(a.time_limit), "--compact"],
                                   input=scene, capture_output=True, text=True)
                seconds = time.perf_counter() - start
                if r.returncode == 2:
                    print(f"{n:>7} {seed:>4} {load:>7.1e} {'refused':<14} {'':>8} {'':>8} {seconds:>8.2f}")
                    continue
                d = json.loads(r.stdout)
                g = d["diagnostics"]
                note = "" if g["status"] == "ok" else "  " + g["status_message"][:80]
                print(f"{n:>7} {seed:>4} {load:>7.1e} {g['status']:<14} {len(d['contacts']):>8} "
                      f"{g['load_fraction']:>8.4g} {seconds:>8.2f} {d['hysteretic_friction']:>14.10f} {g['rounds']:>6} "
                      f"{g['iterations']:>5}{note}", flush=True)


if __name__ == "__main__":
    main()
