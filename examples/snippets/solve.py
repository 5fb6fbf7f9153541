# README example (Python): the scene of examples/snippets/scene.json as a dict.
# Run: PYTHONPATH=build/python /usr/bin/python3 examples/snippets/solve.py
import rhabel

scene = {"material": {"alpha": 0.3, "E1": 1.0e6, "nu": 0.4, "coulomb": 0.5},
         "speed": 0.01,
         "indentors": [{"shape": "parabolic", "radius": 0.02, "load": 100.0},
                       {"shape": "wedge", "slope_leading": 0.05, "slope_trailing": 0.08,
                        "load": 50.0, "apex": 0.02}]}
r = rhabel.solve(scene, grid=401)
print(f"beta = {r.beta:.6g}, kappa = {r.kappa:.6g}, regime {r.regime}, status {r.diagnostics.status}")
for ind in r.indentors:
    a, b = ind.contact
    peak = "singular" if ind.peak_pressure is None else f"{ind.peak_pressure:.6g} Pa"
    print(f"{ind.shape:9s} contact [{a:.6g}, {b:.6g}] m, C_f = {ind.hysteretic_friction:.6g}, "
          f"C_f + k = {ind.total_friction:.6g}, peak {peak} at {ind.peak_pressure_at:.6g} m")
    for e in ind.edges:
        print(f"    {e.side:8s} edge: p ~ K d^{e.exponent:.6g}")
p = r.indentors[0].pressure          # NumPy arrays x [m], p [Pa] on 401 points inside the contact
print(f"parabola pressure samples: {p.x.size}, max {p.p.max():.6g} Pa")
a, b = r.indentors[0].contact        # the solved pressure at points of one's own: pressure_at
print(f"parabola pressure at the contact's centre: {r.indentors[0].pressure_at((a + b) / 2):.6g} Pa")
