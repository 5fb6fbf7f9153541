#!/usr/bin/env python3
"""A sampled-profile scene for `rhabel solve -` (the cost of rhabel::punch::solve_profile against
the number of contacts): N cosine bumps of period 1 whose heights vary by 20 % (a slower sine of
period 3.7), S samples per period (default 80), alpha 0.3, E1 = 1, speed 1, body load P (default
N / 200).

    python3 studies/scenes/cosine_profile.py 50 | build/bin/rhabel solve - --acceptance 1e-6
    python3 studies/scenes/cosine_profile.py 100 20 0.25 | build/bin/rhabel solve - --acceptance 1e-6
"""
import json
import math
import sys

periods = int(sys.argv[1]) if len(sys.argv) > 1 else 10
per_period = int(sys.argv[2]) if len(sys.argv) > 2 else 80
load = float(sys.argv[3]) if len(sys.argv) > 3 else periods / 200
n = per_period * periods
x = [-0.5 + periods * i / (n - 1) for i in range(n)]
z = [0.05 * math.cos(2 * math.pi * v) * (1 + 0.2 * math.sin(2 * math.pi * v / 3.7)) for v in x]
json.dump({"description": f"{periods} cosine bumps, {n} samples",
           "material": {"alpha": 0.3, "E1": 1.0, "nu": 0.0, "coulomb": 0.0}, "speed": 1.0,
           "body": {"load": load},
           "profile": {"x": x, "z": z}}, sys.stdout)
