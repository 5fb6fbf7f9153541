"""rhabel.sweep: the rows of `rhabel sweep`, by the same code (the scene layer's sweep and its
pool of threads): equal bit for bit but the seconds, in rows and in the output file; resuming an
interrupted output file; the command line's refusals as ValueError."""

import csv
import io
import json
import subprocess

import pytest

import rhabel
from conftest import SOURCE_DIR, sigint_after

RUBBER_SWEEP = SOURCE_DIR / "examples" / "friction_speed_sweep.json"
TWO = {"scene": {"material": {"alpha": 0.3, "E1": 1.0e6, "nu": 0.5, "coulomb": 0.2}, "speed": 0.01,
                 "indentors": [{"shape": "parabolic", "radius": 0.02, "load": 100.0},
                               {"shape": "wedge", "slope_leading": 0.05, "slope_trailing": 0.08, "load": 50.0,
                                "apex": 0.01}]},
       "axes": [{"path": "indentors[1].apex", "values": [0.01, 0.02]},
                {"path": "material.alpha", "range": {"from": 0.1, "to": 0.7, "count": 3}},
                {"path": "speed", "values": [0.01, -1.0]}]}


def without_seconds(rows):
    return [{k: v for k, v in row.items() if k != "seconds"} for row in rows]


def command_line_rows(cli, path, tmp_path, *args):
    out = tmp_path / "cli.jsonl"
    run = subprocess.run([str(cli), "sweep", str(path), "--out", str(out), "--jsonl", "--quiet", *args],
                         capture_output=True, text=True)
    assert run.returncode in (0, 3), run.stderr
    return [json.loads(line) for line in out.read_text().splitlines()]


def csv_without_seconds(text):
    rows = list(csv.reader(io.StringIO(text)))
    column = rows[0].index("seconds")
    return [row[:column] + row[column + 1:] for row in rows]


def test_master_curve_sweep_equals_the_command_line(cli, tmp_path):
    ours = rhabel.sweep(RUBBER_SWEEP, progress=False)
    theirs = command_line_rows(cli, RUBBER_SWEEP, tmp_path)
    assert len(ours) == 41 and all(row.status == "ok" for row in ours)
    assert without_seconds(ours) == without_seconds(theirs)


@pytest.mark.parametrize("threads", [1, 0])
def test_a_sweep_dict_equals_the_command_line(cli, tmp_path, threads):
    path = tmp_path / "two.json"
    path.write_text(json.dumps(TWO))
    ours = rhabel.sweep(TWO, threads=threads, progress=False, tolerance=1e-10)
    theirs = command_line_rows(cli, path, tmp_path, "--tolerance", "1e-10")
    assert [row.row for row in ours] == list(range(12))
    # The negative speed is a row of its own (invalid_scene), not a refusal of the sweep.
    assert {row.status for row in ours if row.speed < 0} == {"invalid_scene"}
    assert without_seconds(ours) == without_seconds(theirs)


def test_profile_knots_reach_every_row(cli, tmp_path):
    # profile_knots / --profile-knots: the rough example at acceptance 1e-11 is ok with the spline's
    # knots in its densities, equal to the command line's rows, and not ok without them (the series
    # alone ends at a residual of ~4.5e-10).
    knots = {"scene": str(SOURCE_DIR / "examples" / "rough_profile.json"),
             "axes": [{"path": "body.load", "values": [5.0, 4.0]}]}
    path = tmp_path / "knots.json"
    path.write_text(json.dumps(knots))
    ours = rhabel.sweep(knots, progress=False, acceptance=1e-11, profile_knots=True)
    theirs = command_line_rows(cli, path, tmp_path, "--acceptance", "1e-11", "--profile-knots")
    assert [row.status for row in ours] == ["ok", "ok"]
    assert without_seconds(ours) == without_seconds(theirs)
    assert all(row.status != "ok" for row in rhabel.sweep(knots, progress=False, acceptance=1e-11))


def test_the_output_file_equals_the_command_lines_and_resumes(cli, tmp_path):
    path = tmp_path / "two.json"
    path.write_text(json.dumps(TWO))
    ours = tmp_path / "ours.csv"
    rows = rhabel.sweep(path, out=ours, progress=False)
    cli_out = tmp_path / "cli.csv"
    subprocess.run([str(cli), "sweep", str(path), "--out", str(cli_out), "--quiet"], capture_output=True, check=False)
    assert csv_without_seconds(ours.read_text()) == csv_without_seconds(cli_out.read_text())
    assert without_seconds(rows) == without_seconds(rhabel.sweep(path, progress=False))
    # Interrupted: the header, four rows and a torn fifth line. Rerun: the four rows are kept
    # (their seconds too), the others solved, the file whole and in row order again.
    lines = ours.read_text().splitlines(keepends=True)
    ours.write_text("".join(lines[:5]) + lines[5][:20])
    resumed = rhabel.sweep(path, out=ours, progress=False)
    assert ours.read_text().splitlines(keepends=True)[:5] == lines[:5]
    assert csv_without_seconds(ours.read_text()) == csv_without_seconds(cli_out.read_text())
    assert [row.seconds for row in resumed[:4]] == [row.seconds for row in rows[:4]]


@pytest.mark.parametrize("edit, words", [
    (lambda s: s["axes"][0].update(path="indentors[0].raduis"), ["indentors[0].raduis"]),
    (lambda s: s.update(combine="cross"), ["combine", "cross"]),
    (lambda s: s["axes"][1]["range"].update(count=0), ["count"]),
])
def test_refusals_name_the_field(edit, words):
    bad = json.loads(json.dumps(TWO))
    edit(bad)
    with pytest.raises(ValueError) as e:
        rhabel.sweep(bad, progress=False)
    assert "\n" not in str(e.value)
    for word in words:
        assert word in str(e.value)


def test_a_value_json_has_not_is_refused():
    bad = json.loads(json.dumps(TWO))
    bad["scene"]["speed"] = object()
    with pytest.raises(ValueError, match=r"sweep: scene.speed = <object .* is not a JSON value \(type object\)"):
        rhabel.sweep(bad, progress=False)


def test_another_sweeps_file_is_refused(tmp_path):
    out = tmp_path / "other.csv"
    out.write_text("row,speed,status\n0,1,ok\n")
    with pytest.raises(ValueError, match="another header"):
        rhabel.sweep(TWO, out=out, progress=False)
    assert out.read_text() == "row,speed,status\n0,1,ok\n"


def test_a_file_is_resumed_only_under_its_options(tmp_path):
    # Each row records the options it was solved with; another acceptance or tolerance is refused
    # (the file untouched), the same ones resume (here: nothing to solve, the file unchanged).
    out = tmp_path / "two.csv"
    rows = rhabel.sweep(TWO, out=out, progress=False, tolerance=1e-6, acceptance=1e-4)
    assert all(row.tolerance == 1e-6 and row.acceptance == 1e-4 for row in rows)
    assert all(row.acceptance is None for row in rhabel.sweep(TWO, progress=False))
    before = out.read_text()
    for options in ({"tolerance": 1e-6}, {"tolerance": 1e-7, "acceptance": 1e-4}):
        with pytest.raises(ValueError, match=r"line 2 was solved with tolerance 1e-06, acceptance 0\.0001, this run asks"):
            rhabel.sweep(TWO, out=out, progress=False, **options)
        assert out.read_text() == before
    assert without_seconds(rhabel.sweep(TWO, out=out, progress=False, tolerance=1e-6, acceptance=1e-4)) == \
        without_seconds(rows)
    assert out.read_text() == before


def test_ctrl_c_stops_a_sweep_and_keeps_the_rows_done(tmp_path):
    # Ctrl-C (SIGINT) during a sweep whose rows each refine for seconds (the periodic example at
    # acceptances it cannot reach): KeyboardInterrupt, the rows under way stopped (their solves
    # poll the same flag), the output file holding only whole rows, so that the sweep resumes.
    # The bound of 5 s is the contract ("within a second") with a margin for a loaded machine.
    import time

    scene = rhabel.load_scene(SOURCE_DIR / "examples" / "rough_periodic.json")
    slow = {"scene": scene, "axes": [{"path": "speed", "values": [0.01, 0.02, 0.03, 0.04]}]}
    out = tmp_path / "slow.csv"
    with sigint_after(0.5) as sent:
        rhabel.sweep(slow, out=out, threads=2, progress=False, acceptance=1e-9)
    assert sent and time.monotonic() - sent[0] < 5
    lines = out.read_text().splitlines(keepends=True)
    assert lines[0].startswith("row,speed,tolerance,acceptance,profile_knots,status")
    assert all(line.endswith("\n") for line in lines)
    assert not any(",error," in line for line in lines[1:])  # a stopped row is not written as a row
