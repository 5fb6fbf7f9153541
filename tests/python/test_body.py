"""Indentors on one rigid body (scene "body"): rhabel.solve splits the body's load so that every
indentor has the same level approach + height. Checks that hold whatever the numbers (the split
itself is checked against the boundary-element oracle in tests/punch/test_coupled_bem.cpp)."""
import copy
import json
import pathlib

import pytest

import rhabel

EXAMPLES = pathlib.Path(__file__).resolve().parents[2] / "examples"
# The acceptance of an `ok` result (punch::solve_options::acceptance), relative to the scale named
# at each use.
ACCEPTANCE = 1e-9


@pytest.fixture(scope="module")
def array():
    scene = json.loads((EXAMPLES / "asperity_array.json").read_text())
    return scene, rhabel.solve(scene)


def test_loads_add_up_and_levels_agree(array):
    scene, r = array
    assert r.diagnostics.status == "ok"
    total = scene["body"]["load"]
    assert abs(sum(c.load for c in r.indentors) / total - 1) < ACCEPTANCE
    spans = max(c.contact_length for c in r.indentors)
    slope = spans / (2 * scene["indentors"][0]["radius"])  # largest |f'| on a contact
    for c, spec in zip(r.indentors, scene["indentors"]):
        level = c.approach + spec.get("height", 0.0)
        assert abs(level - r.body_approach) < ACCEPTANCE * slope * spans


def test_raised_asperity_carries_less(array):
    scene, r = array
    loads = [c.load for c in r.indentors]
    raised = next(i for i, s in enumerate(scene["indentors"]) if s.get("height", 0) > 0)
    assert loads[raised] == min(loads)


def test_per_indentor_solve_reproduces_the_offsets(array):
    # The same indentors with the body's loads given one by one: the relative vertical offsets
    # (paper, end of section 3) are the heights.
    scene, r = array
    per = copy.deepcopy(scene)
    del per["body"]
    for spec, c in zip(per["indentors"], r.indentors):
        spec.pop("height", None)
        spec["load"] = c.load
    q = rhabel.solve(per)
    assert q.diagnostics.status == "ok"
    assert "body_approach" not in q
    spans = max(c.contact_length for c in r.indentors)
    for spec, c, d in zip(scene["indentors"], r.indentors, q.indentors):
        assert abs((d.approach - q.indentors[0].approach) - (c.approach - r.indentors[0].approach)) < 1e-7 * spans
        assert abs(d.contact[0] - c.contact[0]) < 1e-7 * spans


@pytest.mark.parametrize("change, message", [
    (lambda s: s["body"].update(load=0.0), "body.load = 0"),
    (lambda s: s["body"].update(weight=1.0), "body.weight is not a known field"),
    (lambda s: s["indentors"][0].update(load=1.0), "indentors[0].load is not used on a rigid body"),
    (lambda s: s["indentors"][1].update(height=float("inf")), "indentors[1].height"),
    (lambda s: s.pop("body"), "indentors[0].load"),
    (lambda s: (s.pop("body"), [d.update(load=1.0) for d in s["indentors"]]), "indentors[2].height needs a rigid body"),
])
def test_bad_body_scenes_name_the_field(array, change, message):
    scene = copy.deepcopy(array[0])
    change(scene)
    with pytest.raises(ValueError, match=message.replace("[", r"\[").replace("]", r"\]")):
        rhabel.solve(scene)


def test_threads_give_the_same_result(array):
    # solve_options::threads: the Jacobian's columns in parallel; each column depends on its index
    # alone, so the result is the same bit for bit.
    scene, r = array
    q = rhabel.solve(scene, threads=3)
    assert [c.contact for c in q.indentors] == [c.contact for c in r.indentors]
    assert [c.load for c in q.indentors] == [c.load for c in r.indentors]
    for bad in (-1, 1025, 2.0, True):
        with pytest.raises(ValueError, match="threads"):
            rhabel.solve(scene, threads=bad)
