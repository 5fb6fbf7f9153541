"""rhabel.solve with a measured master curve ("material": {"master_curve": ...}): the fixed point
of the command line's own code (the scene layer), so the same fit and the same numbers as
`rhabel solve`, bit for bit; the curve's path relative to the scene file with load_scene; the
command line's refusals."""

import json
import shutil
import subprocess

import pytest

import rhabel
from conftest import SOURCE_DIR

CURVE = SOURCE_DIR / "examples" / "materials" / "filled_rubber.csv"


def rubber(**extra):
    return {"master_curve": str(CURVE), "temperature": 40.0, "wlf": {"C1": 8.86, "C2": 101.6, "T_ref": 20.0},
            "nu": 0.5, "coulomb": 0.0, **extra}


SLIDER = {"material": rubber(name="filled rubber"), "speed": 0.01,
          "indentors": [{"shape": "parabolic", "radius": 0.01, "load": 500.0}]}
PAIR = {"material": rubber(), "speed": 1e-3,
        "indentors": [{"shape": "parabolic", "radius": 0.01, "load": 500.0},
                      {"shape": "wedge", "slope_leading": 0.1, "slope_trailing": 0.1, "load": 200.0, "apex": 0.01}]}


def command_line(cli, path, *args, returncode=0):
    run = subprocess.run([str(cli), "solve", str(path), "--compact", *args], capture_output=True, text=True)
    assert run.returncode == returncode, run.stderr
    doc = json.loads(run.stdout)
    del doc["diagnostics"]["seconds"]
    return doc


@pytest.mark.parametrize("scene", [SLIDER, PAIR], ids=["one parabola", "parabola and wedge"])
def test_equals_the_command_line(cli, tmp_path, scene):
    path = tmp_path / "scene.json"
    path.write_text(json.dumps(scene))
    expected = command_line(cli, path)
    ours = rhabel.solve(rhabel.load_scene(path)).to_plain()
    del ours["diagnostics"]["seconds"]
    assert ours["material_fit"]["status"] == "ok"
    assert ours == expected


def test_a_periodic_profile_equals_the_command_line(cli, tmp_path):
    # The rough profile of examples/rough_periodic.json on the rubber (boundary-element solver,
    # whose contact width is the fixed point's length), at the acceptance of the command line.
    scene = json.loads((SOURCE_DIR / "examples" / "rough_periodic.json").read_text())
    scene["material"] = rubber()
    scene["profile"]["file"] = str(SOURCE_DIR / "examples" / scene["profile"]["file"])
    path = tmp_path / "rough.json"
    path.write_text(json.dumps(scene))
    expected = command_line(cli, path, "--acceptance", "1e-3")
    ours = rhabel.solve(rhabel.load_scene(path), acceptance=1e-3).to_plain()
    del ours["diagnostics"]["seconds"]
    assert ours == expected


def test_the_fitted_material_solves_like_a_power_law():
    # The result is the scene solved with the fitted (alpha, E1): the same numbers as that scene
    # given with alpha and E1 directly.
    r = rhabel.solve(SLIDER)
    fit = r.material_fit
    assert fit.status == "ok" and fit.iterations > 1 and fit.window[0] < fit.omega0 < fit.window[1]
    direct = rhabel.solve({**SLIDER, "material": {"alpha": fit.alpha, "E1": fit.E1, "nu": 0.5, "coulomb": 0.0,
                                                  "name": "filled rubber"}})
    assert r.indentors[0].contact == direct.indentors[0].contact
    assert r.indentors[0].hysteretic_friction == direct.indentors[0].hysteretic_friction
    assert r.scene["material"] == direct.scene["material"]
    # omega0 = U / L at the fixed point (the fixed point's own tolerance on ln omega0).
    assert fit.omega0 == pytest.approx(SLIDER["speed"] / fit.contact_length, rel=1e-6)


def test_load_scene_resolves_the_curve_against_the_scene_file(tmp_path):
    (tmp_path / "curves").mkdir()
    shutil.copy(CURVE, tmp_path / "curves" / "rubber.csv")
    (tmp_path / "scenes").mkdir()
    scene = json.loads(json.dumps(SLIDER))
    scene["material"]["master_curve"] = "../curves/rubber.csv"
    path = tmp_path / "scenes" / "slider.json"
    path.write_text(json.dumps(scene))
    ours = rhabel.solve(rhabel.load_scene(path))
    assert ours.material_fit.alpha == rhabel.solve(SLIDER).material_fit.alpha


@pytest.mark.parametrize("edit, words", [
    (lambda m: m.update(master_curve="/nonexistent/curve.csv"), ["material.master_curve", "/nonexistent/curve.csv"]),
    (lambda m: m.pop("wlf"), ["temperature", "wlf"]),
    (lambda m: m.update(alpha=0.3), ["alpha", "master_curve"]),
    (lambda m: m.update(nu=0.7), ["material.nu", "0.7"]),
])
def test_refusals_name_the_field(edit, words):
    scene = json.loads(json.dumps(SLIDER))
    edit(scene["material"])
    with pytest.raises(ValueError) as e:
        rhabel.solve(scene)
    message = str(e.value)
    assert "\n" not in message
    for word in words:
        assert word in message, message


@pytest.mark.parametrize("speed, length, shift", [(0.02, 1e-3, True), (1e-6, 1e-3, False), (10.0, 1e-4, True)])
def test_fit_material_equals_the_command_line(cli, speed, length, shift):
    args = [str(cli), "fit-material", str(CURVE), "--speed", repr(speed), "--length", repr(length), "--json"]
    kwargs = {}
    if shift:
        args += ["--temperature", "40", "--wlf", "8.86,101.6,20"]
        kwargs = {"temperature": 40, "wlf": {"C1": 8.86, "C2": 101.6, "T_ref": 20}}
    run = subprocess.run(args, capture_output=True, text=True)
    assert run.returncode in (0, 3), run.stderr
    assert rhabel.fit_material(CURVE, speed, length, **kwargs) == json.loads(run.stdout)
    # The tuple form of the WLF constants is the same request.
    if shift:
        assert rhabel.fit_material(CURVE, speed, length, temperature=40, wlf=(8.86, 101.6, 20)) == json.loads(run.stdout)


@pytest.mark.parametrize("kwargs, words", [
    ({"speed": 0.0}, ["speed", "0.0"]),
    ({"length": float("nan")}, ["length", "nan"]),
    ({"speed": None}, ["speed", "None", "not a number"]),
    ({"temperature": 40.0, "wlf": 5}, ["wlf", "C1, C2, T_ref"]),
    ({"temperature": float("inf"), "wlf": (8.86, 101.6, 20.0)}, ["temperature", "inf"]),
    ({"temperature": 40.0}, ["temperature", "wlf"]),
    ({"temperature": 40.0, "wlf": {"C1": 8.86, "C2": 101.6}}, ["wlf", "T_ref"]),
    ({"temperature": 40.0, "wlf": (8.86, -1.0, 20.0)}, ["C2", "> 0"]),
    ({"window_decades": 9.0}, ["window_decades", "9.0"]),
    ({"curve": "/nonexistent.csv"}, ["/nonexistent.csv"]),
])
def test_fit_material_refusals(kwargs, words):
    call = {"curve": CURVE, "speed": 0.02, "length": 1e-3, **kwargs}
    with pytest.raises(ValueError) as e:
        rhabel.fit_material(**call)
    assert "\n" not in str(e.value)
    for word in words:
        assert word in str(e.value), str(e.value)
