"""Errors: scene validation (same decisions and messages as the command line), and the mapping of
library exceptions to Python (std::invalid_argument, std::domain_error -> ValueError with the same
message; std::overflow_error -> OverflowError)."""

import copy
import json
import subprocess

import numpy as np
import pytest

import rhabel
from conftest import parabola_scene

GOOD = {"material": {"alpha": 0.3, "E1": 1.0e6, "nu": 0.5, "coulomb": 0.0}, "speed": 0.01,
        "indentors": [{"shape": "parabolic", "radius": 0.02, "load": 100.0}]}


def edited(path, value):
    """GOOD with the field at `path` (a tuple of keys) set to value, or removed if value is DELETE."""
    scene = copy.deepcopy(GOOD)
    node = scene
    for key in path[:-1]:
        node = node[key]
    if value is DELETE:
        del node[path[-1]]
    else:
        node[path[-1]] = value
    return scene


DELETE = object()

# (name, scene, words the message must contain). Every scene is also valid JSON, so that the
# command line can be asked about the same input.
BAD_SCENES = [
    ("missing_material", edited(("material",), DELETE), ["material", "missing"]),
    ("missing_speed", edited(("speed",), DELETE), ["speed", "missing", "(0, inf)"]),
    ("missing_alpha", edited(("material", "alpha"), DELETE), ["material.alpha", "missing", "[0, 1)"]),
    ("missing_radius", edited(("indentors", 0, "radius"), DELETE), ["indentors[0].radius", "missing"]),
    ("missing_shape", edited(("indentors", 0, "shape"), DELETE), ["indentors[0].shape", "missing"]),
    ("missing_indentors", edited(("indentors",), DELETE), ["indentors", "missing"]),
    ("unknown_top", edited(("sped",), 2), ["sped", "not a known field"]),
    ("unknown_material", edited(("material", "E2"), 3), ["material.E2", "not a known field"]),
    ("radius_on_wedge",
     edited(("indentors",), [{"shape": "wedge", "slope_leading": 0.1, "slope_trailing": 0.1, "radius": 1, "load": 1}]),
     ["indentors[0].radius", "not a known field", "wedge"]),
    ("unknown_shape", edited(("indentors", 0, "shape"), "cone"), ["indentors[0].shape", "cone", "parabolic"]),
    ("negative_radius", edited(("indentors", 0, "radius"), -2), ["indentors[0].radius = -2", "(0, inf)"]),
    ("alpha_one", edited(("material", "alpha"), 1.0), ["material.alpha = 1.0", "[0, 1)"]),
    ("nu_too_big", edited(("material", "nu"), 0.6), ["material.nu = 0.6", "[0, 0.5]"]),
    ("negative_coulomb", edited(("material", "coulomb"), -0.1), ["material.coulomb", "[0, inf)"]),
    ("zero_speed", edited(("speed",), 0), ["speed = 0", "(0, inf)"]),
    ("zero_load", edited(("indentors", 0, "load"), 0.0), ["indentors[0].load = 0.0", "(0, inf)"]),
    ("string_number", edited(("speed",), "1"), ["speed", "must be a number", "a string"]),
    ("boolean_number", edited(("speed",), True), ["speed", "must be a number", "a boolean"]),
    ("null_number", edited(("speed",), None), ["speed", "must be a number", "null"]),
    ("empty_indentors", edited(("indentors",), []), ["indentors is empty"]),
    ("indentors_object", edited(("indentors",), {"a": 1}), ["indentors", "array"]),
    ("material_array", edited(("material",), [1, 2]), ["material", "object"]),
    ("name_number", edited(("indentors", 0, "name"), 3), ["indentors[0].name", "must be a string"]),
    ("second_indentor",
     edited(("indentors",), GOOD["indentors"] + [{"shape": "flat", "width": -1, "load": 1}]),
     ["indentors[1].width = -1", "(0, inf)"]),
    ("load_on_body", edited(("body",), {"load": 50.0}), ["indentors[0].load", "not used on a rigid body"]),
    ("height_without_body", edited(("indentors", 0, "height"), 1e-3), ["indentors[0].height", "needs a rigid body"]),
    ("body_not_object", edited(("body",), 3), ["body", "object"]),
    ("body_unknown_field",
     {**edited(("body",), {"load": 1.0, "weight": 2}), "indentors": [{"shape": "parabolic", "radius": 0.02}]},
     ["body.weight", "not a known field"]),
    ("body_negative_load",
     {**edited(("body",), {"load": -1.0}), "indentors": [{"shape": "parabolic", "radius": 0.02}]},
     ["body.load = -1", "(0, inf)"]),
    ("profile_and_indentors", {**GOOD, "body": {"load": 1.0}, "profile": {"x": [0, 1, 2, 3], "z": [0, 1, 0, -1]}},
     ["indentors and profile are exclusive"]),
    ("profile_without_body", {**{k: v for k, v in GOOD.items() if k != "indentors"},
                              "profile": {"x": [0, 1, 2, 3], "z": [0, 1, 0, -1]}}, ["profile needs a rigid body"]),
    ("profile_x_string", {**{k: v for k, v in GOOD.items() if k != "indentors"}, "body": {"load": 1.0},
                          "profile": {"x": [0, "a", 2, 3], "z": [0, 1, 0, -1]}}, ["profile.x[1]", "must be a number"]),
    ("profile_unknown_field", {**{k: v for k, v in GOOD.items() if k != "indentors"}, "body": {"load": 1.0},
                               "profile": {"x": [0, 1, 2, 3], "z": [0, 1, 0, -1], "y": 1}},
     ["profile.y", "not a known field"]),
    ("profile_file_and_x", {**{k: v for k, v in GOOD.items() if k != "indentors"}, "body": {"load": 1.0},
                            "profile": {"file": "p.csv", "x": [0, 1]}}, ["profile.x", "not a known field with a file"]),
    ("profile_missing_z", {**{k: v for k, v in GOOD.items() if k != "indentors"}, "body": {"load": 1.0},
                           "profile": {"x": [0, 1, 2, 3]}}, ["profile.z", "missing"]),
]


@pytest.mark.parametrize("name,scene,words", BAD_SCENES, ids=[c[0] for c in BAD_SCENES])
def test_bad_scene_is_one_line_value_error(name, scene, words):
    with pytest.raises(ValueError) as info:
        rhabel.solve(scene)
    message = str(info.value)
    assert "\n" not in message
    for word in words:
        assert word in message, f"{name}: {message!r} lacks {word!r}"


@pytest.mark.parametrize("name,scene,words", BAD_SCENES, ids=[c[0] for c in BAD_SCENES])
def test_messages_equal_the_command_line(cli, tmp_path, name, scene, words):
    path = tmp_path / "scene.json"
    path.write_text(json.dumps(scene))
    run = subprocess.run([str(cli), "solve", str(path)], capture_output=True, text=True)
    assert run.returncode == 2 and run.stdout == ""
    expected = run.stderr.strip()
    prefix = "rhabel: solve: "
    assert expected.startswith(prefix), expected
    with pytest.raises(ValueError) as info:
        rhabel.solve(scene)
    assert str(info.value) == expected[len(prefix):]


def test_python_only_inputs():
    with pytest.raises(ValueError, match="top level must be a JSON object"):
        rhabel.solve([GOOD])
    with pytest.raises(ValueError, match=r"speed = \+inf overflows a double"):
        rhabel.solve(edited(("speed",), float("inf")))
    with pytest.raises(ValueError, match="speed = nan is not a number"):
        rhabel.solve(edited(("speed",), float("nan")))
    with pytest.raises(ValueError, match="overflows a double"):
        rhabel.solve(edited(("speed",), 10 ** 400))
    with pytest.raises(ValueError, match="must be a number"):
        rhabel.solve(edited(("speed",), np.bool_(True)))
    with pytest.raises(ValueError, match="keys must be strings"):
        rhabel.solve(edited((1,), 2))
    with pytest.raises(ValueError, match="grid"):
        rhabel.solve(GOOD, grid=1)
    with pytest.raises(ValueError, match="grid"):
        rhabel.solve(GOOD, grid=2.5)
    # NumPy numbers and tuples are accepted.
    r = rhabel.solve(edited(("indentors",), ({"shape": "parabolic", "radius": np.float32(0.02), "load": np.int64(100)},)))
    assert r.scene["indentors"][0]["load"] == 100.0 and isinstance(r.scene["indentors"][0]["load"], float)


def test_invalid_argument_becomes_value_error_with_the_message():
    # punch::solve throws std::invalid_argument for a tolerance outside (0, 1).
    with pytest.raises(ValueError, match=r"rhabel::punch::solve: options.tolerance must be in \(0, 1\)$"):
        rhabel.solve(GOOD, tolerance=2.0)


def test_nearly_coincident_indentors_are_a_result_not_an_exception():
    # Two identical indentors 1e-4 apart (their isolated contacts overlap, not an error): the
    # coupled solve returns a result with its evidence. Measured: two adjacent contacts, the first
    # wholly ahead of its apex, each carrying its load ("ok"); a non-ok outcome must name both.
    scene = parabola_scene()
    scene["indentors"].append(dict(scene["indentors"][0], apex=1e-4))
    result = rhabel.solve(scene)
    if result.diagnostics.status == "ok":
        first, second = sorted(c.contact for c in result.indentors)
        assert first[1] < second[0]
        for c in result.indentors:
            assert abs(c.load - 100.0) < 1e-9 * 100.0
    else:
        assert result.diagnostics.status == "contacts_merge"
        assert "indentors[0]" in result.diagnostics.status_message
        assert "indentors[1]" in result.diagnostics.status_message


def test_domain_error_becomes_value_error_with_the_message():
    # Quadrature: p <= -1 (throw_bad_parameter: std::domain_error).
    with pytest.raises(ValueError, match=r"^rhabel::quadrature::gauss_jacobi: p = -1 is outside the valid range \(-1, 30\]$"):
        rhabel.gauss_jacobi(4, -1.0, 0.0)
    with pytest.raises(ValueError, match="gauss_jacobi: n = 0"):
        rhabel.gauss_jacobi(0, 0.0, 0.0)
    with pytest.raises(ValueError, match="jacobi_p: x = inf"):
        rhabel.jacobi_p(3, 0.0, 0.0, np.inf)
    with pytest.raises(ValueError, match="abel_parameters: alpha = 1"):
        rhabel.abel.solve(1.0, 0.0, -1, 1, "bounded", "bounded", [1.0])
    with pytest.raises(ValueError, match="solve_abel_rh: beta = -0.5"):
        rhabel.riemann.solve_abel_rh(0.3, -0.5, -1, 1, [1.0])
    with pytest.raises(ValueError, match="not a valid edge class"):
        rhabel.abel.solve(0.3, 0.0, -1, 1, "sharp", "bounded", [1.0])


def test_overflow_error_becomes_overflow_error():
    # A Jacobi series summed far outside [-1, 1] exceeds the double range: std::overflow_error.
    sol = rhabel.abel.solve(0.0, 0.0, -1, 1, "bounded", "bounded", [0.0, 0.0, 0.0, 1.0])
    with pytest.raises(OverflowError):
        sol.density.series(1e200)


def test_callable_errors_propagate():
    def bad(s):
        raise KeyError("from the callable")

    with pytest.raises(KeyError, match="from the callable"):
        rhabel.abel.solve(0.3, 0.0, -1, 1, "bounded", "unbounded", bad)
    with pytest.raises(KeyError, match="from the callable"):
        rhabel.riemann.solve_abel_rh(0.3, 0.0, -1, 1, bad)
    with pytest.raises(TypeError, match=r"data\(s\) must return a real number, got str"):
        rhabel.abel.solve(0.3, 0.0, -1, 1, "bounded", "unbounded", lambda s: "x")
    with pytest.raises(ValueError, match=r"data\(s\) returned nan"):  # a non-finite value names the callable
        rhabel.abel.solve(0.3, 0.0, -1, 1, "bounded", "unbounded", lambda s: float("nan"))
