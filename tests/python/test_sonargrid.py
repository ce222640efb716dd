# SPDX-License-Identifier: GPL-3.0-or-later
# `import sonargrid` (docs/python.md) against `sonargrid-cli`, the contract it mirrors: the same
# settings on a bundled log give the very numbers of the CLI's JSON (compared exactly: both print
# or hold the same doubles), the arrays have the documented shapes, dtypes and origin, and bad
# input raises the module's exceptions with the core's message.
import csv
import math
import pathlib
import re
import subprocess
import sys

import numpy as np
import pytest

import sonargrid

ROOT = pathlib.Path(__file__).resolve().parents[2]

# Three model × rule pairs, each its paper's own rule (docs/models.md).
PAIRS = [("hpf", "addition"), ("himm", "himm"), ("parameterized", "bayes-recursive")]


def test_models_are_the_cli_declarations(cli):
    got = sonargrid.models()
    want = cli("models", "--json")
    got["compatible"] = [list(p) for p in got["compatible"]]
    assert got == want
    names = [m["name"] for m in got["models"]]
    for model in ("hpf", "konolige", "murphy", "parameterized", "himm"):
        assert model in names


def test_log_shapes_and_time_slices(room, datasets):
    # datasets/room/room.sglog: a Pioneer 3-DX ring of 16 sonars (its header's 16 `sonar` lines).
    assert room.ring["robot"] == "p3dx"
    assert room.ring["sonars"].shape == (16, 3)
    assert room.ring["max_range"] == 5.0
    text = (datasets / "room" / "room.sglog").read_text()
    scans = len(re.findall(r"^scan ", text, flags=re.M))
    assert len(room) == scans
    assert room.times.shape == (scans,)
    assert room.odometry.shape == (scans, 3)
    assert room.truth.shape == (scans, 3)
    assert room.readings.shape == (room.reading_count, 4)
    assert np.all(np.diff(room.times) >= 0)
    # Slices are by time in seconds: [t0, t1).
    t0, t1 = room.times[10], room.times[20]
    part = room[t0:t1]
    assert len(part) == 10
    assert part.times[0] == t0
    assert len(room.between(t0, t1)) == 10
    assert len(room[:t1]) + len(room[t1:]) == len(room)
    first = room[0]
    assert first["time"] == room.times[0]
    assert len(first["readings"]) == int(np.sum(room.readings[:, 0] == 0))
    with pytest.raises(IndexError):
        room[len(room)]


@pytest.mark.parametrize("model,rule", PAIRS)
def test_map_equals_cli_map_json(room, cli, datasets, model, rule):
    m = sonargrid.map(room, model=model, rule=rule, cell=0.05)
    want = cli("map", "--log", datasets / "room" / "room.sglog", "--model", model, "--rule", rule,
               "--cell", "0.05", "--json")
    assert m.width == want["grid"]["width"] and m.height == want["grid"]["height"]
    assert m.cell == want["grid"]["cell_m"]
    assert list(m.origin) == want["grid"]["origin"]
    assert m.readings == want["readings"]
    assert m.cells_filled == want["cells_filled"]
    assert m.cv_histogram == want["cv_histogram"]
    assert m.params == want["params"]
    # The arrays: (height, width), the documented dtypes, the same counts as the JSON.
    assert m.levels.shape == (m.height, m.width) and m.levels.dtype == np.uint8
    assert m.p.shape == (m.height, m.width) and m.p.dtype == np.float64
    assert m.observed.dtype == np.bool_ and m.filled.dtype == np.bool_
    assert np.bincount(m.levels.ravel(), minlength=16).tolist() == want["cv_histogram"]
    assert int(m.filled.sum()) == want["cells_filled"]
    assert np.all((m.p >= 0) & (m.p <= 1))
    # Never-observed cells hold p = 0.5, level 8, except under the HIMM histogram, which has no
    # "unknown": CV = 0, p = 0 (docs/models.md, the rules' table; paper 000 §2.2).
    unknown_p, unknown_level = (0.0, 0) if rule == "himm" else (0.5, 8)
    assert np.all(m.p[~m.observed] == unknown_p) and np.all(m.levels[~m.observed] == unknown_level)
    # levels and observed share the map's memory, read-only.
    assert not m.levels.flags.owndata and not m.levels.flags.writeable
    assert not m.observed.flags.owndata


def test_forward_model_equals_cli_map_json(room, cli, datasets):
    # docs/forward-model.md: the forward model learned by EM, its rule EM itself, as the CLI maps it.
    m = sonargrid.map(room, model="forward-em", rule="em", cell=0.05, iterations=3)
    want = cli("map", "--log", datasets / "room" / "room.sglog", "--model", "forward-em",
               "--iterations", "3", "--cell", "0.05", "--json")
    assert m.readings == want["readings"]
    assert m.cells_filled == want["cells_filled"]
    assert m.cv_histogram == want["cv_histogram"]
    assert m.params == want["params"]
    assert np.all(m.p[~m.observed] == 0.5) and np.all(m.levels[~m.observed] == 8)
    with pytest.raises(ValueError, match="cannot be used with rule"):
        sonargrid.map(room, model="forward-em", rule="bayes")


def test_origin_is_the_lower_left_corner(room):
    # Row 0 is the grid's lowest y: the cell holding the first odometry position is the one at
    # floor((x - origin) / cell) and was observed (a sonar mounted 0.14 m away looked past it).
    m = sonargrid.map(room, model="himm", rule="himm")
    x, y, _ = room.odometry[0]
    ox, oy = m.origin
    assert ox <= x < ox + m.width * m.cell and oy <= y < oy + m.height * m.cell
    i, j = int((y - oy) // m.cell), int((x - ox) // m.cell)
    assert 0 <= i < m.height and 0 <= j < m.width


@pytest.mark.parametrize("model,rule", PAIRS)
def test_score_equals_cli_score_json(room, cli, datasets, model, rule):
    ref = sonargrid.read_reference(datasets / "room" / "room.json")
    got = sonargrid.score(sonargrid.map(room, model=model, rule=rule), ref)
    want = cli("score", "--log", datasets / "room" / "room.sglog", "--reference",
               datasets / "room" / "room.json", "--model", model, "--rule", rule, "--json")
    assert got == want
    assert list(got) == list(want)  # the same keys in the same order
    assert "iop_mm" in got and got["iop_mm"] > 0


def test_score_options_and_common_cells(room, cli, datasets):
    ref = sonargrid.read_reference(datasets / "room" / "room.json")
    m = sonargrid.map(room, model="hpf", rule="bayes", epsilon=0.2)
    got = sonargrid.score(m, ref, metrics=["iop", "correlation"], iop_weight="level")
    want = cli("score", "--log", datasets / "room" / "room.sglog", "--reference",
               datasets / "room" / "room.json", "--model", "hpf", "--rule", "bayes",
               "--set", "epsilon=0.2", "--metrics", "iop,correlation", "--iop-weight", "level",
               "--json")
    assert got == want
    # Scoring on every cell equals scoring on a mask of every cell; on the map's own observed
    # cells (the common cells of one map) unobserved cells drop out of cells_evaluated.
    all_cells = sonargrid.score(m, ref, cells=np.ones((m.height, m.width), dtype=bool))
    assert all_cells == sonargrid.score(m, ref)
    own = sonargrid.score(m, ref, cells=[])
    assert own["cells_evaluated"] <= all_cells["cells_evaluated"]


def test_goodness_equals_cli_goodness_json(cli, datasets):
    run1 = datasets / "arafat-room" / "run-1.sglog"
    run2 = datasets / "arafat-room" / "run-2.sglog"
    m = sonargrid.map(sonargrid.read_log(run1), model="parameterized", rule="bayes-recursive")
    got = sonargrid.goodness(m, second_log=sonargrid.read_log(run2))
    want = cli("goodness", "--log", run1, "--second-log", run2, "--model", "parameterized",
               "--rule", "bayes-recursive", "--json")
    assert got == want
    assert got["vsdns"] is not None and got["two_run_positive"] > 0


def test_sweep_rows_equal_the_cli_csv(room, cli, datasets, tmp_path):
    ref = sonargrid.read_reference(datasets / "room" / "room.json")
    grid = ["p5=10,25", "p2=0.05:0.05:0.1"]
    rows = sonargrid.sweep(room, model="parameterized", rule="bayes-recursive", grid=grid,
                           ties=["p1=1-p4"], metrics=["vsdns", "iop"], reference=ref,
                           as_frame=False)
    out = tmp_path / "sweep.csv"
    cli("sweep", "--log", datasets / "room" / "room.sglog", "--reference",
        datasets / "room" / "room.json", "--model", "parameterized", "--rule", "bayes-recursive",
        "--grid", grid[0], "--grid", grid[1], "--tie", "p1=1-p4", "--metric", "vsdns",
        "--metric", "iop", "--csv", out, json_output=False)
    lines = [l for l in out.read_text().splitlines() if not l.startswith("#")]
    want = list(csv.DictReader(lines))
    assert len(rows) == len(want) == 4
    for got, w in zip(rows, want):
        assert list(got) == list(w)
        for key, value in w.items():
            expected = None if value == "" else float(value)
            assert got[key] == expected, key
    # The dict form of the grid gives the same sets; and the thread count changes nothing.
    again = sonargrid.sweep(room, model="parameterized", rule="bayes-recursive",
                            grid={"p5": [10, 25], "p2": [0.05, 0.1]}, ties="p1=1-p4",
                            metrics=["vsdns", "iop"], reference=ref, threads=1, as_frame=False)
    assert again == rows


def test_same_map_at_any_thread_count(room):
    one = sonargrid.map(room, model="konolige", rule="logodds", threads=1)
    two = sonargrid.map(room, model="konolige", rule="logodds", threads=2)
    three = sonargrid.map(room, model="konolige", rule="logodds", threads=3)
    for other in (two, three):
        assert np.array_equal(one.levels, other.levels)
        assert one.p.tobytes() == other.p.tobytes()


def test_exports_equal_the_cli_files(room, cli, datasets, tmp_path):
    m = sonargrid.map(room, model="himm", rule="himm")
    m.to_png(tmp_path / "py.png", legend=True, scale=2)
    m.to_ros(str(tmp_path / "py"))
    cli("map", "--log", datasets / "room" / "room.sglog", "--model", "himm", "--rule", "himm",
        "--png", tmp_path / "cli.png", "--legend", "--scale", "2", "--ros-map", tmp_path / "cli",
        json_output=False)
    assert (tmp_path / "py.png").read_bytes() == (tmp_path / "cli.png").read_bytes()
    assert (tmp_path / "py.pgm").read_bytes() == (tmp_path / "cli.pgm").read_bytes()
    assert (tmp_path / "py.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_start_pose_places_the_odometry_as_the_cli(cli, datasets, tmp_path):
    # The room log with its odometry starting at (0, 0, 0), as a robot switched on where it stood
    # records it (convert --start-pose 0,0,0); its first true pose is (1.5 m, 1 m, 0), and there
    # its odometry is the true pose again (the room's odometry equals its true pose).
    zero = tmp_path / "room-from-zero.sglog"
    cli("convert", "--in", datasets / "room" / "room.sglog", "--out", zero, "--start-pose", "0,0,0",
        json_output=False)
    log = sonargrid.read_log(zero)
    assert tuple(log.odometry[0]) == (0.0, 0.0, 0.0)
    placed = sonargrid.read_log(zero, start_pose=(1.5, 1.0, 0.0))
    assert tuple(placed.odometry[0]) == (1.5, 1.0, 0.0)
    assert np.max(np.abs(placed.odometry - placed.truth)) < 1e-12
    ref = sonargrid.read_reference(datasets / "room" / "room.json")
    got = sonargrid.score(sonargrid.map(placed, model="himm", rule="himm"), ref)
    want = cli("score", "--log", zero, "--start-pose", "1.5,1,0", "--reference",
               datasets / "room" / "room.json", "--model", "himm", "--rule", "himm", "--json")
    assert got["iop_mm"] == want["iop_mm"]
    with pytest.raises(ValueError, match="start_pose: expected THETA in degrees"):
        sonargrid.read_log(zero, start_pose=(0.0, 0.0, 400.0))


def test_errors_carry_the_core_message(room, tmp_path):
    missing = tmp_path / "nothing.sglog"
    with pytest.raises(sonargrid.LogError, match=re.escape(str(missing))):
        sonargrid.read_log(missing)
    bad = tmp_path / "bad.sglog"
    original = (ROOT / "datasets" / "room" / "room.sglog").read_text().splitlines()
    text = list(original)
    # The first scan line with its range turned into garbage: the error names file and line.
    k = next(i for i, l in enumerate(text) if l.startswith("scan "))
    text[k + 1] = text[k + 1].split(" ")[0] + " x y z"
    bad.write_text("\n".join(text[: k + 5]) + "\n")
    with pytest.raises(sonargrid.LogError, match=re.escape(f"{bad}:{k + 2}")):
        sonargrid.read_log(bad)
    assert issubclass(sonargrid.LogError, sonargrid.Error)
    with pytest.raises(sonargrid.ParameterError, match="p5"):
        sonargrid.map(room, model="parameterized", rule="bayes", p5=400)
    with pytest.raises(sonargrid.ParameterError, match="no_such"):
        sonargrid.map(room, model="hpf", rule="bayes", no_such=1)
    with pytest.raises(ValueError, match="unknown model 'sonic'"):
        sonargrid.map(room, model="sonic", rule="bayes")
    with pytest.raises(ValueError, match="cannot be used with rule"):
        sonargrid.map(room, model="hpf", rule="himm")
    with pytest.raises(ValueError, match="threads"):
        sonargrid.map(room, model="hpf", rule="bayes", threads=0)
    # A log whose scans carry no true pose (`scan T X Y THETA none`, docs/formats.md) cannot be
    # mapped from the true pose.
    no_truth = tmp_path / "no-truth.sglog"
    no_truth.write_text("\n".join(re.sub(r"^(scan \S+ \S+ \S+ \S+) .*$", r"\1 none", l)
                                  for l in original[: k + 17]) + "\nend\n")
    log = sonargrid.read_log(no_truth)
    assert not log.has_truth and np.isnan(log.truth).all()
    with pytest.raises(sonargrid.Error, match="no true pose"):
        sonargrid.map(log, model="hpf", rule="bayes", pose="truth")
    with pytest.raises(sonargrid.ParameterError, match="p9"):
        sonargrid.sweep(room, model="parameterized", rule="bayes", grid=["p9=1,2"], as_frame=False)


def test_docs_example_runs(tmp_path):
    # docs/python.md's example, run as a user would paste it (from the repository root).
    text = (ROOT / "docs" / "python.md").read_text()
    blocks = re.findall(r"```python\n(.*?)```", text, flags=re.S)
    assert blocks, "docs/python.md has no python example"
    example = blocks[0]
    assert len(example.strip().splitlines()) <= 25
    script = tmp_path / "example.py"
    script.write_text(example)
    out = subprocess.run([sys.executable, str(script)], cwd=ROOT, capture_output=True, text=True)
    assert out.returncode == 0, out.stderr
    assert "IOP" in out.stdout


def test_mapping_releases_the_gil(datasets):
    # While a map of the office log (7001 scans) is built on another Python thread, this thread
    # keeps running Python: with the GIL held for the whole map it could not take a single step
    # until the map was done.
    import threading

    office = sonargrid.read_log(datasets / "office" / "office.sglog")
    done = threading.Event()

    def work():
        sonargrid.map(office, model="hpf", rule="bayes", threads=1)
        done.set()

    thread = threading.Thread(target=work)
    steps = 0
    thread.start()
    while not done.is_set():
        steps += 1
        done.wait(0.001)
    thread.join()
    assert steps > 3, steps
