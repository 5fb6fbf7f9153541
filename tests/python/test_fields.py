"""The fields of a result in Python: each contact's pressure_at(x), graded pressure samples, and
the surface of several contacts on one grid (the command line's, bit for bit)."""
import json
import math
import subprocess

import numpy as np
import pytest

import rhabel
from conftest import SOURCE_DIR

TWO = {"material": {"alpha": 0.3, "E1": 1.0, "nu": 0.3, "coulomb": 0.3}, "speed": 1.0,
       "indentors": [{"shape": "parabolic", "radius": 1.0, "load": 1.0},
                     {"shape": "parabolic", "radius": 0.5, "load": 0.5, "apex": 1.6}]}


def test_pressure_at_equals_the_samples_and_takes_any_shape():
    r = rhabel.solve(rhabel.load_scene(SOURCE_DIR / "examples" / "default_scene.json"), grid=101)
    for c in r.indentors:
        assert isinstance(c, rhabel.Contact)
        p = c.pressure_at(c.pressure.x)
        peak = np.max(np.abs(c.pressure.p))
        # The solve's coordinates are relative to the first apex: x -> x - apex rounds by ~eps.
        assert np.max(np.abs(p - c.pressure.p)) <= 1e-12 * peak
        a, b = c.contact
        assert c.pressure_at(a - 1.0) == 0.0 and isinstance(c.pressure_at(0.5 * (a + b)), float)
        grid = np.linspace(a, b, 12).reshape(3, 4)
        assert c.pressure_at(grid).shape == (3, 4)
        assert np.array_equal(c.pressure_at(list(grid.ravel())), c.pressure_at(grid).ravel())
    with pytest.raises(ValueError, match="not finite"):
        r.indentors[0].pressure_at([0.0, math.nan])


def test_pressure_at_integrates_to_the_load():
    # Gauss-Jacobi with the contact's own edge exponents: p = (b - x)^del (x - a)^gam s(x), s
    # smooth, so sum w_k s(x_k) is int p to the series' accuracy.
    r = rhabel.solve({**TWO, "indentors": TWO["indentors"][:1]})
    c = r.indentors[0]
    (a, b), lead, trail = c.contact, c.edges[0], c.edges[1]
    x, b_minus_x, x_minus_a, w = rhabel.gauss_jacobi(64, trail.exponent, lead.exponent, a, b)
    smooth = c.pressure_at(x) / (b_minus_x ** trail.exponent * x_minus_a ** lead.exponent)
    assert abs(w @ smooth / c.load - 1) < 1e-12


def test_graded_samples_show_the_edge_law():
    r = rhabel.solve({**TWO, "indentors": TWO["indentors"][:1]}, grid=400, spacing="graded")
    c = r.indentors[0]
    a, b = c.contact
    d = c.pressure.x[0] - a
    assert d == pytest.approx((b - a) * math.sin(math.pi / 1600) ** 2, rel=1e-9)
    lead = c.edges[0]
    assert c.pressure.p[0] == pytest.approx(lead.intensity_factor * d ** lead.exponent, rel=1e-4)
    uniform = rhabel.solve({**TWO, "indentors": TWO["indentors"][:1]}, grid=400)
    assert uniform.indentors[0].pressure.x[0] - a == pytest.approx((b - a) / 800, rel=1e-9)
    with pytest.raises(ValueError, match="spacing"):
        rhabel.solve(TWO, grid=5, spacing="chebyshev")


def test_surface_joins_the_contacts_and_equals_the_command_line(cli, tmp_path):
    r = rhabel.solve(TWO, grid=50)
    x, w = r.surface.x, r.surface.w
    assert x.shape == w.shape == (100,)
    for c, spec in zip(r.indentors, TWO["indentors"]):
        a, b = c.contact
        inside = (x > a) & (x < b)
        assert inside.any()
        rigid = -(x[inside] - spec.get("apex", 0.0)) ** 2 / (2 * spec["radius"]) + c.approach
        assert np.max(np.abs(w[inside] - rigid)) <= 1e-12 * np.max(np.abs(w))
    path = tmp_path / "two.json"
    path.write_text(json.dumps(TWO))
    prefix = tmp_path / "two"
    run = subprocess.run([str(cli), "solve", str(path), "--grid", "50", "--csv", str(prefix)], capture_output=True,
                         text=True, check=True)
    document = json.loads(run.stdout)
    assert document["surface"]["x"] == x.tolist() and document["surface"]["w"] == w.tolist()
    table = np.loadtxt(f"{prefix}_surface.csv", delimiter=",", skiprows=1)
    assert np.array_equal(table[:, 0], x) and np.array_equal(table[:, 1], w)
    assert (tmp_path / "two_surface.csv").read_text().startswith("x,displacement\n")
    single = rhabel.solve({**TWO, "indentors": TWO["indentors"][:1]}, grid=50)
    assert "surface" not in single


def test_a_result_pickles_and_copies():
    import copy
    import pickle
    r = rhabel.solve(TWO, grid=5)
    x = np.mean(r.indentors[0].contact)
    deep = copy.deepcopy(r)
    assert deep.indentors[0].pressure_at(x) == r.indentors[0].pressure_at(x)
    assert copy.copy(r.indentors[1]).pressure_at(x) == r.indentors[1].pressure_at(x)
    back = pickle.loads(pickle.dumps(r))
    assert back.to_plain() == r.to_plain() and isinstance(back.indentors[0], rhabel.Contact)
    with pytest.raises(RuntimeError, match="unpickled"):
        back.indentors[0].pressure_at(x)
