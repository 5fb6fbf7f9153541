#!/usr/bin/env bash
# The main job (`make demo`, after the Release build): solves the shipped default scene
# examples/default_scene.json, prints a summary table, and writes into out/:
#   out/default_scene.json              the full result (rhabel solve --grid 201)
#   out/default_scene_pressure.csv      indentor,x,pressure
#   out/default_scene_displacement.csv  indentor,x,displacement
#   out/default_scene.png               pressure and surface displacement (scripts/plot_scene.py)
# The plot uses Debian's matplotlib through /usr/bin/python3 explicitly (the PATH python3 may be a
# pyenv one without it). If plotting fails, the summary is still printed and the reason given.
# Usage: scripts/demo.sh [SCENE.json]; environment: RHABEL (the binary, default build/bin/rhabel),
# RHABEL_PYTHON (default /usr/bin/python3).
set -euo pipefail
cd "$(dirname "$0")/.."
rhabel=${RHABEL:-./build/bin/rhabel}
scene=${1:-examples/default_scene.json}
name=$(basename "$scene" .json)
mkdir -p out

"$rhabel" solve "$scene" --grid 201 --csv "out/$name" > "out/$name.json"

py=${RHABEL_PYTHON:-/usr/bin/python3}  # Debian python3 with python3-matplotlib
[ -x "$py" ] || py=python3
"$py" - "out/$name.json" <<'PY'
import json, sys
r = json.load(open(sys.argv[1]))
s = r["scene"]; m = s["material"]
print(f"rhabel demo: {sys.argv[1]}")
print(f"  material: {m.get('name', '')}  alpha = {m['alpha']}, E1 = {m['E1']:.4g} Pa s^alpha, "
      f"nu = {m['nu']}, Coulomb k = {m['coulomb']}; speed U = {s['speed']} m/s")
why = " (nu = 0.5: incompressible, so beta = 0 whatever k)" if m["nu"] == 0.5 else ""
print(f"  beta = {r['beta']:.6g}{why}, kappa = {r['kappa']:.6g}, "
      f"regime: {r['regime']} (alpha + beta/2 vs 1/2), E_U = {r['effective_modulus']:.6g} Pa")
hdr = f"  {'indentor':<20} {'a [mm]':>9} {'b [mm]':>9} {'L [mm]':>8} {'eps':>7} {'load [N/m]':>10} " \
      f"{'C_f':>9} {'C_f + k':>9} {'peak p [MPa]':>13} {'at [mm]':>8}"
print(hdr); print("  " + "-" * (len(hdr) - 2))
for i, ind in enumerate(r["indentors"]):
    a, b = ind["contact"]
    eps = f"{ind['epsilon']:.4f}" if "epsilon" in ind else "-"
    peak = "singular" if ind["peak_pressure_singular"] else f"{ind['peak_pressure'] * 1e-6:.4f}"
    print(f"  {ind.get('name', ind['shape']):<20} {a*1e3:9.4f} {b*1e3:9.4f} {ind['contact_length']*1e3:8.4f} "
          f"{eps:>7} {ind['load']:10.4g} {ind['hysteretic_friction']:9.5f} {ind['total_friction']:9.5f} "
          f"{peak:>13} {ind['peak_pressure_at']*1e3:8.4f}")
d = r["diagnostics"]
print(f"  solver: status {d['status']}, max residual of eq. (8) {d['residual']:.2e}, {d['seconds']*1e3:.1f} ms")
PY

rm -f "out/$name.png"  # never leave a stale plot next to fresh numbers
if "$py" scripts/plot_scene.py "out/$name.json" "out/$name.png" 2> "out/$name.plot.log"; then
  rm -f "out/$name.plot.log"
  echo "  wrote out/$name.json, out/${name}_pressure.csv, out/${name}_displacement.csv, out/$name.png"
else
  echo "  wrote out/$name.json and the CSV files; NO PNG: plotting failed ($(tail -n 1 "out/$name.plot.log"))." \
       "Install python3-matplotlib (Debian) for /usr/bin/python3." >&2
fi
