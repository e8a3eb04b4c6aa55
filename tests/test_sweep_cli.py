"""``mobility sweep``: the summary, CSV, JSON, files, pictures and one-line errors."""

from __future__ import annotations

import csv
import io
import json

import numpy as np
import pytest

import mobility
from mobility.cli import main
from mobility.errors import RequestError
from mobility.report.sweep import sweep_csv, sweep_json, sweep_summary
from mobility.report.sweep_plot import MAX_SLICES, plot_sweep

from conftest import MECHANISMS

PARALLELOGRAM = str(MECHANISMS / "parallelogram.yaml")
THREE_PRS = str(MECHANISMS / "3prs.yaml")
FIVE_BAR = str(MECHANISMS / "planar_5r.yaml")


def run(capsys, *args):
    status = main([str(a) for a in args])
    out, err = capsys.readouterr()
    return status, out, err


def test_summary_names_the_change_points(capsys):
    status, out, err = run(capsys, "sweep", PARALLELOGRAM, "--vary", "O1=0:360:361", "--no-progress")
    assert status == 0 and err == ""
    assert "assembled: 361 of 361 poses" in out
    assert "359  DOF 1  1T      mobility 1" in out and "2  DOF 2  1T1R    mobility 2" in out
    assert "singular poses (2):" in out
    assert "O1=120 deg: the end effector gains 1 freedom(s): 2 DOF (1T1R); the mechanism gains 1 freedom(s): mobility 2" in out
    assert "O1=300 deg" in out and "between 4 pair(s) of neighbouring poses" in out


def test_csv_has_a_header_then_one_row_per_pose(capsys):
    status, out, _ = run(capsys, "sweep", THREE_PRS, "--vary", "P1=-20:20:3", "--vary", "P2=-20:20:4", "--format", "csv")
    rows = list(csv.reader(io.StringIO(out)))
    assert status == 0
    assert rows[0][:5] == ["P1 [mm]", "P2 [mm]", "dof", "pattern", "mobility"]
    assert rows[0][-3:] == ["verdict", "conditioning", "actuation_margin"]
    assert len(rows) == 1 + 12
    assert [(r[0], r[1]) for r in rows[1:5]] == [("-20", "-20"), ("-20", "-6.66667"), ("-20", "6.66667"), ("-20", "20")]
    r = mobility.sweep(mobility.load(THREE_PRS), ["P1=-20:20:3", "P2=-20:20:4"])
    for row, i in zip(rows[1:], range(12)):
        assert (int(row[2]), row[3], int(row[4]), row[-3]) == (r.dof[i], r.pattern[i], r.mobility[i], r.verdict[i])
        assert float(row[-2]) == pytest.approx(r.conditioning[i], rel=1e-5)


def test_unassembled_rows_have_empty_answers():
    r = mobility.sweep(mobility.load(FIVE_BAR), ["A1=-40:40:5", "A2=-40:40:5"])
    rows = list(csv.DictReader(io.StringIO(sweep_csv(r))))
    missing = [row for row in rows if row["assembled"] == "false"]
    assert len(rows) == 25 and missing and len(missing) == int((~r.assembled).sum())
    assert all(row["dof"] == row["pattern"] == row["verdict"] == "" for row in missing)


def test_json_and_output_file(capsys, tmp_path):
    target = tmp_path / "sweep.json"
    status, out, _ = run(capsys, "sweep", PARALLELOGRAM, "--vary", "O1=0:360:13", "--json", "-o", target)
    assert status == 0 and out.startswith(f"wrote {target}: 13 poses")
    data = json.loads(target.read_text())
    assert data["shape"] == [13] and data["assembled"] == 13
    assert [p["values"] for p in data["singular_poses"]] == [{"O1": 120.0}, {"O1": 300.0}]
    assert data["regular"] == {"dof": 1, "pattern": "1T", "mobility": 1, "verdict": None}
    assert data["columns"]["mobility"][4] == 2 and data["columns"]["O1"][4] == 120.0
    assert data == json.loads(sweep_json(mobility.sweep(mobility.load(PARALLELOGRAM), ["O1=0:360:13"])))


def test_plot_files(capsys, tmp_path):
    for vary, kind in ((["O1=0:360:37"], "curve"), (["O1=0:360:9", "A1=0:0:1"], "map")):
        target = tmp_path / f"{kind}.png"
        args = ["sweep", PARALLELOGRAM, "--plot", target] + [x for v in vary for x in ("--vary", v)]
        status, out, _ = run(capsys, *args)
        assert status == 0 and f"wrote {target}: {kind}" in out
        assert target.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def _gids(fig, gid: str) -> int:
    return sum(1 for ax in fig.axes for artist in ax.get_children() if artist.get_gid() == gid)


def test_pictures_mark_what_the_sweep_found():
    curve = plot_sweep(mobility.sweep(mobility.load(PARALLELOGRAM), ["O1=0:360:37"]))
    assert _gids(curve, "mobility:sweep:singular") == 2
    five = mobility.sweep(mobility.load(FIVE_BAR), ["A1=-10:30:9", "P=60:100:9"])
    picture = plot_sweep(five)
    assert _gids(picture, "mobility:sweep:map") == 1 and _gids(picture, "mobility:sweep:regions") == 1
    markers = [a for ax in picture.axes for a in ax.get_children() if a.get_gid() == "mobility:sweep:singular"]
    assert len(markers) == 1 and len(markers[0].get_offsets()) == len(five.singular)
    assert np.allclose(np.asarray(markers[0].get_offsets())[:, 1], 90.0)
    slices = plot_sweep(mobility.sweep(mobility.load(THREE_PRS), ["P1=-10:10:3", "P2=-10:10:3", "P3=-10:10:8"]))
    assert _gids(slices, "mobility:sweep:map") == MAX_SLICES
    with pytest.raises(RequestError, match="cannot be drawn"):
        plot_sweep(mobility.sweep(mobility.load(THREE_PRS), ["P1=0:1:1", "P2=0:1:1", "P3=0:1:1", "R1=0:1:1"]))


def test_progress_bar_on_request(capsys):
    status, _, err = run(capsys, "sweep", PARALLELOGRAM, "--vary", "O1=0:90:4", "--progress")
    assert status == 0 and "closing loops" in err and "analysing" in err


@pytest.mark.parametrize(
    "args, message",
    [
        (["--vary", "Q1=0:1:2"], "'Q1' is not a joint of"),
        (["--vary", "O1=0:1:0"], "COUNT must be at least 1, got 0"),
        (["--vary", "O1=0:1"], "expected NAME=START:STOP:COUNT"),
        (["--vary", "O1=0:1:2", "--vary", "A1=0:1:2", "--max-poses", "3"], "the grid has 4 poses, more than --max-poses 3"),
        (["--vary", "O1=0:1:2", "--plot", "out.gif"], "--plot out.gif: cannot tell the picture type"),
        (["--vary", "O1=0:1:2", "--inputs", "Z9"], "unknown joint 'Z9'"),
        (["--vary", "O1=0:1:2", "--workers", "0"], "--workers must be at least 1"),
        (["--vary", "O1=0:1:2", "--tol", "0.5"], "--tol must lie in"),
    ],
)
def test_bad_input_is_one_line_and_exit_two(capsys, args, message):
    status, out, err = run(capsys, "sweep", PARALLELOGRAM, *args)
    assert status == 2 and out == ""
    assert message in err and err.count("\n") == 1 and "Traceback" not in err


def test_a_joint_that_cannot_be_driven_names_the_file(capsys):
    status, _, err = run(capsys, "sweep", THREE_PRS, "--vary", "S2=0:10:3")
    assert status == 2 and err.strip() == (
        f"mobility: --vary S2=0:10:3: S2 is an S joint of {THREE_PRS}; only R, H, C joints (by their angle, in degrees) "
        "and P joints (by their slide) can be swept"
    )


def test_a_bad_file_is_one_line(capsys, write_yaml):
    path = write_yaml("name: x\nground: g\nend_effector: e\njoints:\n  - {name: A, type: R, links: [g, e], axis: [0, 0], point: [0, 0, 0]}\n")
    status, _, err = run(capsys, "sweep", path, "--vary", "A=0:1:2")
    assert status == 2 and f"{path}:5:" in err and err.count("\n") == 1


def test_summary_of_a_sweep_with_nothing_assembled():
    r = mobility.sweep(mobility.load(PARALLELOGRAM), ["O1=10:20:3", "O2=0:0:1"])  # O2 held while O1 turns: cannot close
    text = sweep_summary(r)
    assert "assembled: 0 of 3 poses" in text and "not assembled: 3 poses" in text
    assert r.regular is None and r.singular == () and len(r.changes) == 0
