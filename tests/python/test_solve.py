"""rhabel.solve against oracles that share no code with the solver: the parabola's closed form
(contact length, trailing edge, C_f, load), Hertz at alpha = 0, and the command line's JSON output
for the shipped default scene."""

import json
import math
import subprocess

import numpy as np
import pytest

import rhabel
from conftest import EPS, SOLVE_TOLERANCE, SOURCE_DIR, parabola_scene


def parabola_closed_form(alpha, E1, nu, k, speed, radius, load, apex):
    """Contact [a, b] and C_f of a parabola (docs/theory.md sections 2 and 5):
    int g = cos(beta pi/2) L^(2-alpha) B(gam+1, del+1) / (pi R Gamma(2-alpha)), load = (pi/2) E_U int g,
    E_U = E1 Gamma(1-alpha) U^alpha / (1-nu^2), gam = (1-2alpha-beta)/2, del = (1+beta)/2,
    tan(beta pi/2) = k (1-2nu) / (2(1-nu)), C_f = (alpha+beta)(2-alpha) L / ((1-alpha)(3-alpha) R),
    b - apex = L (1-2alpha-beta) / (2(1-alpha))."""
    beta = 2 / math.pi * math.atan(k * (1 - 2 * nu) / (2 * (1 - nu)))
    E_U = E1 * math.gamma(1 - alpha) * speed ** alpha / (1 - nu ** 2)
    gam, dl = (1 - 2 * alpha - beta) / 2, (1 + beta) / 2
    B = math.gamma(gam + 1) * math.gamma(dl + 1) / math.gamma(gam + dl + 2)
    integral = load / (math.pi / 2 * E_U)
    L = (integral * math.pi * radius * math.gamma(2 - alpha) / (math.cos(beta * math.pi / 2) * B)) ** (1 / (2 - alpha))
    b = apex + L * (1 - 2 * alpha - beta) / (2 * (1 - alpha))
    cf = (alpha + beta) * (2 - alpha) * L / ((1 - alpha) * (3 - alpha) * radius)
    return {"beta": beta, "a": b - L, "b": b, "L": L, "C_f": cf, "E_U": E_U}


@pytest.mark.parametrize("alpha", [0.0, 0.2, 0.45, 0.7])
@pytest.mark.parametrize("k", [0.0, 0.5, 2.0])
def test_parabola_matches_closed_form(alpha, k):
    nu, E1, speed, R, P, apex = 0.3, 2.0e6, 0.05, 0.01, 250.0, 1e-3
    exact = parabola_closed_form(alpha, E1, nu, k, speed, R, P, apex)
    scene = {"material": {"alpha": alpha, "E1": E1, "nu": nu, "coulomb": k}, "speed": speed,
             "indentors": [{"shape": "parabolic", "radius": R, "load": P, "apex": apex}]}
    r = rhabel.solve(scene)
    ind = r.indentors[0]
    L = exact["L"]
    assert r.beta == pytest.approx(exact["beta"], rel=64 * EPS, abs=64 * EPS)  # one atan, a few roundings
    assert r.effective_modulus == pytest.approx(exact["E_U"], rel=64 * EPS)
    # Edges, length and C_f: the solve's tolerance is the contract (measured a few 1e-15).
    assert ind.contact_length == pytest.approx(L, rel=SOLVE_TOLERANCE)
    assert ind.contact[0] == pytest.approx(exact["a"], abs=SOLVE_TOLERANCE * L)
    assert ind.contact[1] == pytest.approx(exact["b"], abs=SOLVE_TOLERANCE * L)
    assert ind.hysteretic_friction == pytest.approx(exact["C_f"], rel=SOLVE_TOLERANCE, abs=SOLVE_TOLERANCE * L / R)
    assert ind.total_friction == pytest.approx(exact["C_f"] + k, rel=SOLVE_TOLERANCE, abs=SOLVE_TOLERANCE * L / R)
    assert ind.load == pytest.approx(P, rel=SOLVE_TOLERANCE)
    assert ind.status == "ok" and r.diagnostics.status == "ok"
    assert ind.residual < 1e-12  # measured <= 6e-14 (contact.hpp)


def test_hertz_at_alpha_zero():
    """Elastic frictionless limit: a = sqrt(4 R P / (pi E*)), p(x) = p0 sqrt(1 - x^2/a^2),
    p0 = 2 P / (pi a) (Johnson, Contact Mechanics, 4.45)."""
    E1, nu, R, P = 1.0e6, 0.3, 0.02, 100.0
    r = rhabel.solve(parabola_scene(alpha=0.0, nu=nu, E1=E1, radius=R, load=P), grid=41)
    ind = r.indentors[0]
    a_hertz = math.sqrt(4 * R * P / (math.pi * E1 / (1 - nu ** 2)))
    p0 = 2 * P / (math.pi * a_hertz)
    assert ind.contact[0] == pytest.approx(-a_hertz, rel=SOLVE_TOLERANCE)
    assert ind.contact[1] == pytest.approx(a_hertz, rel=SOLVE_TOLERANCE)
    assert abs(ind.hysteretic_friction) < SOLVE_TOLERANCE
    assert ind.peak_pressure == pytest.approx(p0, rel=1e-9)  # the peak is located by a 1-D search
    x, p = ind.pressure.x, ind.pressure.p
    assert isinstance(x, np.ndarray) and isinstance(p, np.ndarray) and x.shape == p.shape == (41,)
    assert np.all((x > -a_hertz) & (x < a_hertz))
    hertz = p0 * np.sqrt(1 - (x / a_hertz) ** 2)
    assert np.max(np.abs(p - hertz)) <= 1e-12 * p0  # the series is exact to rounding at alpha = 0
    w = ind.displacement
    assert w.x.shape == w.w.shape == (41,)
    inside = (w.x > ind.contact[0]) & (w.x < ind.contact[1])
    # In contact the surface follows the indentor: f(x) - f(a), f = -x^2/(2R).
    profile = -(w.x[inside] ** 2) / (2 * R) + ind.contact[0] ** 2 / (2 * R)
    assert np.max(np.abs(w.w[inside] - profile)) <= 1e-12 * a_hertz ** 2 / R


def test_result_fields_and_options():
    scene = rhabel.load_scene(SOURCE_DIR / "examples" / "default_scene.json")
    r = rhabel.solve(scene, grid=9, displacement=False, residual=False)
    assert set(r) == {"beta", "kappa", "regime", "effective_modulus", "indentors", "diagnostics", "scene"}
    parabola, wedge = r.indentors
    assert parabola.shape == "parabolic" and wedge.shape == "wedge"
    assert parabola.name == scene["indentors"][0]["name"]
    assert "epsilon" not in parabola and 0 < wedge.epsilon < 1
    assert wedge.peak_pressure is None and wedge.peak_pressure_singular  # apex below the boundary
    assert parabola.peak_pressure > 0 and not parabola.peak_pressure_singular
    assert [e.side for e in wedge.edges] == ["leading", "trailing"]
    assert wedge.pressure.p.shape == (9,) and "displacement" not in wedge  # displacement=False
    assert r.diagnostics.residual is None and parabola.residual is None  # residual=False: not computed
    assert r["indentors"][0]["contact"] == parabola.contact  # dict and attribute access agree
    assert isinstance(r, dict) and r.scene.material.alpha == 0.25 and r.scene.indentors[1].apex == 0.015
    assert isinstance(r.diagnostics, rhabel.Record) and isinstance(wedge.edges[0], rhabel.Record)
    with pytest.raises(AttributeError, match="not a field"):
        r.indentors[0].radius
    assert json.loads(r.to_json())["indentors"][0]["residual"] is None  # JSON null, as the document's


def test_equals_command_line_json(cli):
    """The result document equals `rhabel solve examples/default_scene.json` (and with --grid),
    except the wall time."""
    path = SOURCE_DIR / "examples" / "default_scene.json"
    for grid, extra in ((0, []), (7, ["--grid", "7"])):
        out = subprocess.run([str(cli), "solve", str(path), "--compact", *extra], check=True, capture_output=True,
                             text=True).stdout
        expected = json.loads(out)
        mine = json.loads(rhabel.solve(rhabel.load_scene(path), grid=grid).to_json())
        for doc in (expected, mine):
            doc["diagnostics"].pop("seconds")
        assert mine == expected


def test_load_scene_rejects_duplicate_keys(tmp_path):
    path = tmp_path / "scene.json"
    path.write_text('{"speed": 1, "speed": 2}')
    with pytest.raises(ValueError, match="speed appears twice"):
        rhabel.load_scene(path)


def test_layered_below_selects_the_coupling_basis_not_the_answer():
    """Two parabolas ~1e-2 of a contact length apart (alpha 0.3): the coupling in the boundary-layer
    basis (layered_below=1) and in the Jacobi series alone (0) are two discretisations of the same
    equation; both ok, edges within 1e-10 L (measured in C++: 7e-16 L at this gap)."""
    load = 0.3 * math.pi / 2 * math.gamma(0.7)
    scene = {"material": {"alpha": 0.3, "E1": 1.0, "nu": 0.0, "coulomb": 0.0}, "speed": 1.0,
             "indentors": [{"shape": "parabolic", "radius": 1.0, "load": load, "apex": 0.0},
                           {"shape": "parabolic", "radius": 1.0, "load": load, "apex": 0.258122412441}]}
    layered, series = rhabel.solve(scene, layered_below=1), rhabel.solve(scene, layered_below=0)
    assert layered.diagnostics.status == "ok" and series.diagnostics.status == "ok"
    L = min(c.contact_length for c in layered.indentors)
    for p, q in zip(layered.indentors, series.indentors):
        assert abs(p.contact[0] - q.contact[0]) < 1e-10 * L and abs(p.contact[1] - q.contact[1]) < 1e-10 * L
    for bad in (-1, float("nan"), float("inf")):
        with pytest.raises(ValueError, match="layered_below"):
            rhabel.solve(scene, layered_below=bad)
