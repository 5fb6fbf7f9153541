"""The result's views: a short repr (one line per contact, bounded whatever the grid), to_dict()
(plain Python and the same NumPy arrays), and the type stubs shipped with the package (their
names and parameters against the implementation; mypy on a small program when it is installed)."""

import ast
import inspect
import json
import pathlib
import re
import shutil
import subprocess
import sys

import numpy as np
import pytest

import rhabel
from conftest import SOURCE_DIR, parabola_scene

PACKAGE = pathlib.Path(rhabel.__file__).parent
TWO = {"material": {"alpha": 0.3, "E1": 1.0e6, "nu": 0.4, "coulomb": 0.5}, "speed": 0.01,
       "indentors": [{"shape": "parabolic", "radius": 0.02, "load": 100.0},
                     {"shape": "wedge", "slope_leading": 0.05, "slope_trailing": 0.08, "load": 50.0, "apex": 0.02,
                      "name": "blade"}]}


def test_repr_has_one_line_per_contact_and_does_not_grow_with_the_grid():
    coarse, fine = rhabel.solve(TWO), rhabel.solve(TWO, grid=401)
    text = repr(fine)
    lines = text.splitlines()
    assert len(lines) == 3, text
    assert lines[0].startswith("rhabel.Result: 2 contacts, status ok")
    for line, ind, label in zip(lines[1:], fine.indentors, ("parabolic", "blade")):
        a, b = ind.contact
        assert f"{label}: [{a:.6g}, {b:.6g}], load {ind.load:.6g}, C_f {ind.hysteretic_friction:.6g}, status ok" in line
    # The same summary at any grid (only the residual, an estimate, could differ between the solves).
    assert [re.sub(r"residual \S+", "", s) for s in lines] == [re.sub(r"residual \S+", "", s)
                                                               for s in repr(coarse).splitlines()]
    assert len(text) < 400
    # A nested Record summarises its arrays as NumPy does (first and last entries).
    assert len(repr(fine.indentors[0])) < 2500 and "..." in repr(fine.indentors[0].pressure)


def test_repr_is_bounded_for_many_contacts():
    one = {"shape": "parabolic", "contact": (0.0, 1.0), "load": 1.0, "hysteretic_friction": 0.1, "status": "ok"}
    many = rhabel.Result({"regime": "below", "beta": 0.0, "kappa": 1.0, "indentors": [one] * 1000,
                          "diagnostics": {"status": "ok", "residual": 1e-14}})
    lines = repr(many).splitlines()
    assert len(lines) == 21 and lines[-1] == "  ... 981 more (r.indentors)", lines[-2:]


def test_repr_of_a_profile_names_its_contacts():
    r = rhabel.solve(rhabel.load_scene(SOURCE_DIR / "examples" / "rough_profile.json"), acceptance=1e-6)
    lines = repr(r).splitlines()
    assert len(lines) == 1 + len(r.contacts) and lines[1].startswith("  [0] contact: [")
    assert lines[0].startswith(f"rhabel.Result: {len(r.contacts)} contacts, status {r.diagnostics.status}")


def test_to_dict_is_plain_data_with_the_same_arrays():
    r = rhabel.solve(TWO, grid=11)
    d = r.to_dict()

    def walk(value):
        assert not isinstance(value, rhabel.Record), type(value)
        if isinstance(value, dict):
            assert type(value) is dict
            for v in value.values():
                walk(v)
        elif isinstance(value, (list, tuple)):
            for v in value:
                walk(v)
        else:
            assert value is None or isinstance(value, (str, bool, int, float, np.ndarray)), type(value)

    walk(d)
    assert d["indentors"][0]["pressure"]["p"] is r.indentors[0].pressure.p  # not a copy
    assert d["indentors"][1]["name"] == "blade" and d["diagnostics"]["status"] == "ok"
    # Arrays as lists, tuples as lists: the command line's document, as to_plain() gives it.
    as_json = json.loads(json.dumps(d, default=lambda a: a.tolist()))
    assert as_json == r.to_plain()


def test_trial_interval_and_nested_records_have_to_dict():
    r = rhabel.solve(parabola_scene())
    assert r.indentors[0].edges[0].to_dict() == dict(r.indentors[0].edges[0])
    t = rhabel.trial_interval(parabola_scene(), *r.indentors[0].contact)
    assert type(t.to_dict()) is dict


# ---- type stubs --------------------------------------------------------------------------------

def stub_functions(path):
    """name -> ast.FunctionDef (the first, for overloads) and the set of class names of a .pyi file."""
    tree = ast.parse(path.read_text())
    functions, classes = {}, set()
    for node in tree.body:
        if isinstance(node, ast.FunctionDef):
            functions.setdefault(node.name, node)
        elif isinstance(node, ast.ClassDef):
            classes.add(node.name)
        elif isinstance(node, ast.ImportFrom):
            classes.update(alias.asname or alias.name for alias in node.names)
        elif isinstance(node, ast.AnnAssign):
            classes.add(node.target.id)
    return functions, classes


def parameters(node):
    args = node.args
    return ([a.arg for a in args.posonlyargs + args.args], [a.arg for a in args.kwonlyargs])


@pytest.mark.parametrize("module", [rhabel, rhabel.abel, rhabel.riemann])
def test_stubs_name_every_public_function_with_its_parameters(module):
    stub = PACKAGE / ((module.__name__.split(".")[-1] if module is not rhabel else "__init__") + ".pyi")
    assert (PACKAGE / "py.typed").is_file() and stub.is_file()
    functions, names = stub_functions(stub)
    for name in module.__all__:
        assert name in functions or name in names, f"{stub.name} lacks {name}"
        obj = getattr(module, name)
        if inspect.isfunction(obj):  # Python functions: the stub's parameters are the real ones
            signature = inspect.signature(obj).parameters.values()
            real = ([p.name for p in signature if p.kind == p.POSITIONAL_OR_KEYWORD],
                    [p.name for p in signature if p.kind == p.KEYWORD_ONLY])
            assert parameters(functions[name]) == real, (name, parameters(functions[name]), real)


def test_stubs_type_check_a_program(tmp_path):
    """mypy (Debian python3-mypy) accepts a program using the package and refuses a wrong use."""
    mypy = shutil.which("mypy")
    if mypy is None and subprocess.run([sys.executable, "-c", "import mypy"], capture_output=True).returncode:
        pytest.skip("mypy is not installed (Debian: python3-mypy)")
    good = tmp_path / "good.py"
    good.write_text("import rhabel\n"
                    "r = rhabel.solve({'speed': 1.0}, grid=11)\n"
                    "x: float = r.indentors[0].load\n"
                    "d: dict = r.to_dict()\n"
                    "rule = rhabel.gauss_jacobi(4, 0.5, 0.0)\n"
                    "w = rule.weight.sum()\n"
                    "s = rhabel.abel.solve(0.0, 0.0, -1.0, 1.0, 'bounded', 'bounded', [0.0, -3.14])\n"
                    "g = s.density([0.0, 0.5])\n")
    bad = tmp_path / "bad.py"
    bad.write_text("import rhabel\nrhabel.solve({}, gird=11)\n")
    env = {"MYPYPATH": str(PACKAGE.parent), "PATH": "/usr/bin:/bin"}
    # One run over both files (mypy's first look at NumPy's stubs is most of its time).
    run = subprocess.run([sys.executable, "-m", "mypy", "--no-incremental", "--cache-dir", str(tmp_path / "cache"),
                          str(good), str(bad)], capture_output=True, text=True, env=env, cwd=tmp_path)
    if "No module named mypy" in run.stderr:
        pytest.skip("mypy is not installed for this interpreter")
    errors = [line for line in run.stdout.splitlines() if ": error:" in line]
    assert run.returncode == 1 and errors and all(line.startswith(("bad.py:", str(bad))) and "gird" in line for line in errors), \
        run.stdout + run.stderr
