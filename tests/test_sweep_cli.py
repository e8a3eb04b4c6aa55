"""``mobility sweep``: the summary, CSV, JSON, files, pictures and one-line errors."""

from __future__ import annotations

import csv
import io
import json
import sys
from types import SimpleNamespace

import numpy as np
import pytest

import mobility
from mobility.cli import main
from mobility.errors import RequestError
from mobility.report.sweep import sweep_csv, sweep_json, sweep_summary
from mobility.report.sweep_plot import MAX_SLICES, choose_slices, plot_sweep
from mobility.sweeps import plan_grid

from conftest import MECHANISMS

PARALLELOGRAM = str(MECHANISMS / "parallelogram.yaml")
THREE_PRS = str(MECHANISMS / "3prs.yaml")
FIVE_BAR = str(MECHANISMS / "planar_5r.yaml")
FOUR_BAR = str(MECHANISMS / "four_bar.yaml")
TSAI = str(MECHANISMS / "3upu_singular.yaml")


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
    assert "O1=120 deg: the end effector gains 1 freedom: 2 DOF (1T1R); the mechanism gains 1 freedom: mobility 2" in out
    assert "O1=300 deg" in out and "between 4 pairs of neighbouring poses" in out


def test_csv_has_a_header_then_one_row_per_pose(capsys):
    status, out, _ = run(capsys, "sweep", THREE_PRS, "--vary", "P1=-20:20:3", "--vary", "P2=-20:20:4", "--format", "csv")
    rows = list(csv.reader(io.StringIO(out)))
    assert status == 0
    assert rows[0][:5] == ["P1 [mm]", "P2 [mm]", "dof", "pattern", "mobility"]
    assert rows[0][-7:] == ["verdict", "conditioning", "actuation_margin", "iti", "oti", "lti", "cti"]
    assert len(rows) == 1 + 12
    assert [(r[0], r[1]) for r in rows[1:5]] == [("-20", "-20"), ("-20", "-6.66667"), ("-20", "6.66667"), ("-20", "20")]
    r = mobility.sweep(mobility.load(THREE_PRS), ["P1=-20:20:3", "P2=-20:20:4"])
    for row, i in zip(rows[1:], range(12)):
        assert (int(row[2]), row[3], int(row[4]), row[-7]) == (r.dof[i], r.pattern[i], r.mobility[i], r.verdict[i])
        assert float(row[-6]) == pytest.approx(r.conditioning[i], rel=1e-5)
        assert float(row[-2]) == pytest.approx(r.lti[i], rel=1e-5)


@pytest.mark.parametrize("vary, shown", [
    ("O1=119.999:120.001:5", ["119.999", "119.9995", "120", "120.0005", "120.001"]),
    ("O1=100000:100001:3", ["100000", "100000.5", "100001"]),
])
def test_coordinates_show_the_digits_that_tell_neighbours_apart(capsys, vary, shown):
    status, out, _ = run(capsys, "sweep", PARALLELOGRAM, "--vary", vary, "--format", "csv")
    assert status == 0 and [r[0] for r in list(csv.reader(io.StringIO(out)))[1:]] == shown
    status, out, _ = run(capsys, "sweep", PARALLELOGRAM, "--vary", vary)
    assert f"O1 from {shown[0]} to {shown[-1]} deg" in out


def test_summary_says_when_freedoms_are_left_to_the_solver(capsys):
    status, out, _ = run(capsys, "sweep", TSAI, "--vary", "P1=-30:30:3", "--vary", "P2=-30:30:3")
    assert status == 0 and "note: 2 coordinates driven for mobility 3: the other 1 freedom follows the solver" in out
    status, out, _ = run(capsys, "sweep", TSAI, "--vary", "P1=-30:30:3", "--vary", "P2=-30:30:3", "--vary", "P3=0:0:1")
    assert status == 0 and "note:" not in out


def test_unassembled_rows_have_empty_answers():
    r = mobility.sweep(mobility.load(FIVE_BAR), ["A1=-40:40:5", "A2=-40:40:5"])
    rows = list(csv.DictReader(io.StringIO(sweep_csv(r))))
    missing = [row for row in rows if row["assembled"] == "false"]
    assert len(rows) == 25 and missing and len(missing) == int((~r.assembled).sum())
    assert all(row["dof"] == row["pattern"] == row["verdict"] == "" for row in missing)
    answers = ("dof", "pattern", "mobility", "smallest_kept", "largest_dropped", "near_singular", "inexact", "verdict", "conditioning", "actuation_margin")
    assert all(row[name] == "" for row in missing for name in answers)
    assert {row["near_singular"] for row in rows if row["assembled"] == "true"} == {"false"}


def test_unassembled_poses_have_no_warnings_in_csv_or_json():
    r = mobility.sweep(mobility.load(FOUR_BAR), ["A=30:40:3"])  # the crank reaches 34 deg: 35 and 40 are not assembled
    assert r.assembled.tolist() == [True, False, False]
    rows = list(csv.DictReader(io.StringIO(sweep_csv(r))))
    assert [(row["near_singular"], row["inexact"]) for row in rows] == [("false", "false"), ("", ""), ("", "")]
    columns = json.loads(sweep_json(r))["columns"]
    assert columns["near_singular"] == columns["inexact"] == [False, None, None]
    assert r.row(1)["near_singular"] is None and r.row(1)["inexact"] is None and r.row(0)["near_singular"] is False


def test_json_and_output_file(capsys, tmp_path):
    target = tmp_path / "sweep.json"
    status, out, _ = run(capsys, "sweep", PARALLELOGRAM, "--vary", "O1=0:360:13", "--json", "-o", target)
    assert status == 0 and out.startswith(f"wrote {target}: 13 poses")
    data = json.loads(target.read_text())
    assert data["shape"] == [13] and data["assembled"] == 13
    assert [p["values"] for p in data["singular_poses"]] == [{"O1": 120.0}, {"O1": 300.0}]
    assert data["regular"] == {"dof": 1, "pattern": "1T", "mobility": 1, "verdict": None}
    assert [p["verdict"] for p in data["singular_poses"]] == [None, None]  # no actuated joints: null, as in "regular"
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


def test_pictures_scale_kappa_from_zero_and_break_the_margin_at_a_gain():
    kappa_map = plot_sweep(mobility.sweep(mobility.load(THREE_PRS), ["P1=-20:20:5", "P2=-20:20:5"]))
    mesh = next(a for ax in kappa_map.axes for a in ax.get_children() if a.get_gid() == "mobility:sweep:map")
    assert mesh.norm.vmin == 0.0 and mesh.norm.vmax == pytest.approx(0.28, abs=0.02)  # kappa 0.22 .. 0.28 here
    r = mobility.sweep(mobility.load(PARALLELOGRAM), ["O1=0:360:37"])
    curve = plot_sweep(r)
    margin = next(line for line in curve.axes[1].get_lines() if line.get_label().startswith("rank margin"))
    y = np.asarray(margin.get_ydata(), dtype=float)
    folded = [p.index for p in r.singular]
    assert folded == [12, 30] and np.isnan(y[folded]).all() and np.isfinite(np.delete(y, folded)).all()
    nothing = plot_sweep(mobility.sweep(mobility.load(FOUR_BAR), ["A=60:180:5"]))
    assert [t.get_text() for t in nothing.texts] == ["no pose of the grid could be assembled"]


def test_singular_poses_of_the_five_bar_have_their_verdict_in_json():
    data = json.loads(sweep_json(mobility.sweep(mobility.load(FIVE_BAR), ["A1=-10:30:9", "P=60:100:9"])))
    assert data["singular_poses"] and {p["verdict"] for p in data["singular_poses"]} == {"actuation-singular"}


def test_slices_of_a_grid_with_a_singular_pose_show_it_and_the_files_pose(capsys, tmp_path):
    r = mobility.sweep(mobility.load(TSAI), ["P1=-4:4:5", "P2=-4:4:5", "P3=-3:3:7"])
    assert [p.values for p in r.singular] == [(0.0, 0.0, 0.0)]
    fig = plot_sweep(r)
    shown = [ax for ax in fig.axes if _gids_of(ax, "mobility:sweep:map")]
    assert len(shown) == MAX_SLICES
    titles = [ax.get_title() for ax in shown]
    assert "P3 = 0 mm (file's pose, 1 singular)" in titles  # the file's pose, dropped before
    assert titles == ["P3 = -3 mm", "P3 = -2 mm", "P3 = -1 mm", "P3 = 0 mm (file's pose, 1 singular)", "P3 = 2 mm", "P3 = 3 mm"]
    assert "6 of 7 values of P3: the file's pose; the 1 value holding singular poses; then values spread over the range" in fig.get_suptitle()
    markers = [a for ax in shown for a in ax.get_children() if a.get_gid() == "mobility:sweep:singular"]
    assert len(markers) == 1 and np.allclose(markers[0].get_offsets(), [[0.0, 0.0]])
    # the command that crashed on a 3-D grid with a singular pose
    target = tmp_path / "slices.png"
    status, out, err = run(capsys, "sweep", TSAI, "--vary", "P1=-4:4:5", "--vary", "P2=-4:4:5", "--vary", "P3=-8:8:9", "--plot", target, "--no-progress")
    assert status == 0 and err == "" and f"wrote {target}: slices" in out
    assert target.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def _gids_of(ax, gid: str) -> int:
    return sum(1 for artist in ax.get_children() if artist.get_gid() == gid)


def _slice_request(singular_slices: list[int], third: str = "P3=-9:9:19") -> SimpleNamespace:
    """What choose_slices reads of a sweep: its axes, shape and singular poses (one on each listed slice)."""
    plan = plan_grid(mobility.load(THREE_PRS), ["P1=0:1:2", "P2=0:1:2", third])
    shape = plan.shape
    singular = [SimpleNamespace(index=int(np.ravel_multi_index((1, 0, k), shape))) for k in singular_slices]
    return SimpleNamespace(axes=plan.axes, shape=shape, singular=tuple(singular))


def test_slices_are_chosen_file_pose_first_then_singular_then_spread():
    slices, note = choose_slices(_slice_request([2, 15]))
    assert slices == (0, 2, 9, 11, 15, 18)
    assert note.startswith("6 of 19 values of P3: the file's pose; the 2 values holding singular poses; then")
    many = [0, 1, 2, 3, 4, 14, 15, 16, 17, 18]  # more singular slices than room: spread over them
    slices, note = choose_slices(_slice_request(many))
    assert slices == (0, 2, 4, 9, 16, 18)
    assert "5 of the 10 values holding singular poses" in note and "spread" not in note
    slices, note = choose_slices(_slice_request([], "P3=1:19:10"))  # the file's pose is not a value: spread alone
    assert slices == (0, 2, 4, 5, 7, 9) and note == "6 of 10 values of P3: values spread over the range"
    assert choose_slices(_slice_request([1], "P3=-2:2:5")) == ((0, 1, 2, 3, 4), "all 5 values of P3")


def test_pictures_say_what_grey_means_and_count_freedoms_in_whole_numbers():
    four = plot_sweep(mobility.sweep(mobility.load(FOUR_BAR), ["A=0:60:13"]))  # beyond 34 deg: not assembled
    legend = [t.get_text() for t in four.axes[0].get_legend().get_texts()]
    assert any("not assembled" in t for t in legend)
    for name, vary in ((FOUR_BAR, "A=0:60:13"), (THREE_PRS, "P1=-30:30:7"), (PARALLELOGRAM, "O1=0:360:37")):
        r = mobility.sweep(mobility.load(name), [vary])
        ticks = plot_sweep(r).axes[0].yaxis.get_majorticklocs()
        low, high = int(r.dof[r.assembled].min()), int(r.mobility[r.assembled].max())
        assert all(float(t).is_integer() for t in ticks) and {low, high} <= {int(t) for t in ticks}
    grey = plot_sweep(mobility.sweep(mobility.load(FIVE_BAR), ["A1=-40:40:5", "A2=-40:40:5"]))
    assert _gids(grey, "mobility:sweep:unassembled") == 1
    assert any("not assembled" in t.get_text() for ax in grey.axes if ax.get_legend() for t in ax.get_legend().get_texts())


def test_a_picture_that_cannot_be_drawn_is_refused_before_the_sweep(capsys, monkeypatch, tmp_path):
    import mobility.cli.sweep as command

    def no_sweep(*args, **kwargs):
        raise AssertionError("the sweep ran")

    monkeypatch.setattr(command, "sweep", no_sweep)
    target = tmp_path / "four.png"
    four = [x for v in ("O1=0:1:1", "A1=0:1:1", "A2=0:1:1", "O2=0:1:1") for x in ("--vary", v)]
    status, out, err = run(capsys, "sweep", PARALLELOGRAM, *four, "--plot", target)
    assert status == 2 and out == "" and err.count("\n") == 1
    assert err == f"mobility: --plot {target}: a sweep of 4 coordinates cannot be drawn; plots show 1 (curve), 2 (map) or 3 (slices)\n"
    monkeypatch.setitem(sys.modules, "matplotlib", None)  # matplotlib not installed
    status, out, err = run(capsys, "sweep", PARALLELOGRAM, "--vary", "O1=0:360:5", "--plot", target)
    assert status == 2 and out == "" and err.count("\n") == 1
    assert "plotting needs matplotlib, which is not installed" in err and "pip install 'mechanism-mobility[plot]'" in err
    assert not target.exists()


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
        (["--vary", "O1=0:1:2", "--inputs", "Z9"], "--inputs Z9: unknown joint 'Z9'; expected one of: O1, A1, A2, O2"),
        (["--vary", "O1=0:1:2", "--inputs", "O1, Z9"], "--inputs O1, Z9: unknown joint 'Z9'"),
        (["--vary", "O1=0:1:2", "--workers", "0"], "--workers must be between 1 and 256"),
        (["--vary", "O1=0:1:2", "--workers", "9" * 30], "--workers must be between 1 and 256 (threads of this process; for more, use --scheduler)"),
        (["--vary", "rz=-1e300:1e300:3"], "the end effector's rotation vector reaches 1e+300 deg, more than half a turn"),
        (["--vary", "rx=1e300:1e300:1", "--vary", "ry=1e300:1e300:1"], "the end effector's rotation vector reaches 1.41421e+300 deg"),
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


def test_large_rotations_and_worker_counts_are_refused_by_the_api_too():
    m = mobility.load(PARALLELOGRAM)
    with pytest.raises(RequestError, match="rotation vector reaches 1e\\+200 deg"):  # was an OverflowError
        mobility.sweep(m, [("rz", 1e200, 1e200, 1)])
    with pytest.raises(RequestError, match="workers must be at most 256"):  # was a ValueError from islice
        mobility.sweep(m, ["O1=0:1:2"], workers=10**30)


@pytest.mark.parametrize("fmt", ["csv", "json"])
def test_tables_are_written_in_pieces_that_make_the_same_text(capsys, tmp_path, fmt, monkeypatch):
    import mobility.cli.sweep as command_module
    from mobility.report import sweep as writers

    r = mobility.sweep(mobility.load(PARALLELOGRAM), ["O1=0:360:25"])
    whole = writers.sweep_csv(r) if fmt == "csv" else writers.sweep_json(r)
    if fmt == "csv":
        pieces = list(writers.sweep_csv_pieces(r, rows=4))
        assert len(pieces) == 7 and "".join(pieces) == whole  # 25 rows in pieces of 4
        assert whole.splitlines()[1:] == [",".join(row) for row in csv.reader(io.StringIO(whole))][1:]
    else:
        pieces = list(writers.sweep_json_pieces(r))
        assert len(pieces) == 2 + len(r.columns) and json.loads(whole) == r.to_dict()
    monkeypatch.setattr(writers, "PIECE_ROWS", 4)
    written: list[str] = []
    real = command_module._write_pieces

    def recorded(handle, parts):
        real(handle, (written.append(part) or part for part in parts))

    monkeypatch.setattr(command_module, "_write_pieces", recorded)
    status, out, _ = run(capsys, "sweep", PARALLELOGRAM, "--vary", "O1=0:360:25", "--format", fmt, "-o", tmp_path / f"t.{fmt}")
    assert status == 0 and (tmp_path / f"t.{fmt}").read_text(encoding="utf-8") == whole + ("" if whole.endswith("\n") else "\n")
    status, out, _ = run(capsys, "sweep", PARALLELOGRAM, "--vary", "O1=0:360:25", "--format", fmt)
    assert status == 0 and out == whole + ("" if whole.endswith("\n") else "\n")
    assert len(written) == (2 * 7 if fmt == "csv" else 2 * len(pieces))  # the command wrote the pieces as they came (file, then stdout)


def test_running_out_of_memory_is_one_line_and_exit_two(capsys, monkeypatch):
    import mobility.cli.sweep as command

    def too_big(*args, **kwargs):
        raise MemoryError()

    monkeypatch.setattr(command, "sweep", too_big)
    status, out, err = run(capsys, "sweep", PARALLELOGRAM, "--vary", "O1=0:1:2")
    assert (status, out) == (2, "")  # was exit 3, an "internal error"
    assert err == ("mobility: out of memory: the request needs more memory than this machine has free; "
                   "ask for less (a coarser grid or fewer poses: --max-poses; fewer samples)\n")


def test_reading_a_sweep_result_wrongly_is_a_request_error():
    r = mobility.sweep(mobility.load(PARALLELOGRAM), ["O1=0:360:13"])
    for call, message in [
        (lambda: r.column("nope"), "no column 'nope'; expected one of: O1, dof, pattern"),  # was a KeyError
        (lambda: r.grid("verdict"), "no column 'verdict'"),  # no inputs were chosen: no actuation columns
        (lambda: r.column(3), "no column 3"),
        (lambda: r.row(13), "row: expected a grid point index in 0..12, got 13"),  # was an IndexError
        (lambda: r.row("a"), "row: expected a grid point index in 0..12, got 'a'"),
        (lambda: r.row(True), "row: expected a grid point index in 0..12, got True"),  # was a TypeError
    ]:
        with pytest.raises(RequestError) as info:
            call()
        assert message in str(info.value)
    assert r.row(-1) == r.row(12) and r.grid("dof").shape == (13,)


@pytest.mark.parametrize("name", ["map.png", "map.SVG", "map.pdf"])
def test_a_picture_name_given_to_o_is_refused_with_the_option_that_draws_it(capsys, tmp_path, name):
    target = tmp_path / name
    status, out, err = run(capsys, "sweep", PARALLELOGRAM, "--vary", "O1=0:360:5", "-o", target)
    assert (status, out) == (2, "") and not target.exists()  # was exit 0 and a text table in map.png
    assert err.strip() == f"mobility: -o {target}: -o writes the table (text, csv or json); a picture is drawn by --plot {target}"


def test_a_summary_with_poses_not_assembled_does_not_say_the_grid_has_no_singular_pose():
    # The crank of the four-bar reaches its limit near 34 deg, a singular pose of the loop; the grid points beyond
    # it are not assembled, so "none on the grid" would claim what nobody looked at.
    part = sweep_summary(mobility.sweep(mobility.load(FOUR_BAR), ["A=30:40:3"]))
    assert "singular poses: none among the assembled poses; the 2 not assembled may hold some" in part
    assert "none on the grid" not in part
    whole = sweep_summary(mobility.sweep(mobility.load(FOUR_BAR), ["A=0:20:3"]))
    assert "singular poses: none on the grid" in whole
