"""Every command, on extreme and large inputs: a right answer with finite numbers, or one line and exit 2.

Issue 13 holds for every command, not only ``analyze``: ``analyze`` (also
``--finite``), ``check``, ``actuation`` (also ``--enumerate`` and
``--samples``), ``plot`` (also ``--graph``), ``jacobian``, ``sweep``,
``view`` (also ``--samples``) and ``convert`` are run in-process
(:func:`mobility.cli.main`) on

* mechanisms at extreme scales (every length times 1e200 or 1e-250, or one
  pivot at 1e300), each run under a SIGALRM time guard;
* large mechanisms (a ladder of 2,001 joints, a parallel mechanism of 180),
  in a child process whose address space is capped (``RLIMIT_AS``): a
  memory blow-up ends there in a ``MemoryError``, reported as a failure,
  instead of in the machine's swap.

A run passes when it ends with exit 0 or 1 (an answer: 1 is a failed check,
an invalid actuation, a singular Jacobian) whose printed numbers (and the
numbers of the picture, page or file it writes) are all finite, with nothing
on stderr but notes (and ``convert``'s line naming the file it wrote); or with exit 2 and one line ``mobility: ...``.  The time
guard is a bound on a hang, not a speed assertion (speed is measured by
``benchmarks/``).

The answers themselves are checked at scale by a second route: the Jacobian
of a mechanism scaled by ``k`` is that of the mechanism at scale 1, each part
scaled by its power of ``k``; the picture and the 3D view of a scaled
mechanism draw the same scene, scaled.
"""

from __future__ import annotations

import contextlib
import dataclasses
import io
import json
import math
import os
import re
import resource
import subprocess
import sys
from pathlib import Path
from typing import Any, Callable

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import mobility
from guards import TookTooLong, finite_numbers, time_bound
from mobility.core.model import Joint, Mechanism

ROOT = Path(__file__).resolve().parent.parent
MECHANISMS = ROOT / "mechanisms"

MEMORY_CAP = 3 << 29
"""Address space of the child process running the large cases (bytes): 1.5 GiB, about three times what
the largest run maps (460 MB, of which the libraries alone are most; 190 MB resident); the plot that
once built every pair of points in every view (24 GB) stops here."""

RUN_BOUND = 60.0
"""Seconds one command may take before the guard stops it (a hang, not a slow run: every run here
takes a few seconds at most)."""


# -- inputs ---------------------------------------------------------------------------------------


def yaml_text(m: Mechanism) -> str:
    """A mechanism file with every number written in full (``repr``: nothing rounded at any scale)."""

    def vec(v: Any) -> str:
        return "[" + ", ".join(repr(float(x)) for x in v) + "]"

    lines = [f"name: {json.dumps(m.name)}", f"ground: {m.ground}", f"end_effector: {m.end_effector}", "joints:"]
    for j in m.world_joints:
        fields = [f"name: {j.name}", f"type: {j.type}", f"links: [{j.links[0]}, {j.links[1]}]"]
        if j.axis is not None:
            fields.append(f"axis: {vec(j.axis)}")
        if j.axes is not None:
            fields.append(f"axes: [{vec(j.axes[0])}, {vec(j.axes[1])}]")
        if j.point is not None and j.type != "P":
            fields.append(f"point: {vec(j.point)}")
        if j.pitch is not None:
            fields.append(f"pitch: {float(j.pitch)!r}")
        if j.normal is not None:
            fields.append(f"normal: {vec(j.normal)}")
        if j.actuated:
            fields.append("actuated: true")
        lines.append("  - {" + ", ".join(fields) + "}")
    return "\n".join(lines) + "\n"


def scaled(m: Mechanism, factor: float) -> Mechanism:
    """``m`` with every length (points, pitches) times ``factor``, written in the global frame."""
    joints = []
    for j in m.world_joints:
        changes: dict[str, Any] = {}
        if j.point is not None:
            changes["point"] = tuple(float(x) * factor for x in j.point)
        if j.pitch is not None:
            changes["pitch"] = j.pitch * factor
        joints.append(dataclasses.replace(j, **changes))
    return m.replace(joints=tuple(joints), frames=())


def ladder(triangles: int) -> Mechanism:
    """A planar ladder of rigid triangles (2 n + 1 joints, series inside parallel n deep), the first pivot actuated."""
    z = (0.0, 0.0, 1.0)
    joints = [Joint(f"A{i}", "R", ("g", f"l{i}"), axis=z, point=(float(i), 0.0, 0.0), actuated=i == 0) for i in range(triangles + 1)]
    joints += [Joint(f"B{i}", "R", (f"l{i}", f"l{i + 1}"), axis=z, point=(i + 0.5, 1.0 + 0.25 * math.sin(i), 0.0)) for i in range(triangles)]
    return Mechanism(f"ladder of {triangles}", "g", f"l{triangles}", tuple(joints))


def prs(limbs: int) -> Mechanism:
    """A parallel mechanism of P-R-S limbs around a circle (3 DOF, 1T2R), the first three sliders actuated."""
    joints = []
    for i in range(limbs):
        c, s = math.cos(2 * math.pi * i / limbs), math.sin(2 * math.pi * i / limbs)
        joints.append(Joint(f"P{i}", "P", ("g", f"a{i}"), axis=(0.0, 0.0, 1.0), actuated=i < 3))
        joints.append(Joint(f"R{i}", "R", (f"a{i}", f"b{i}"), axis=(-s, c, 0.0), point=(c, s, 0.5)))
        joints.append(Joint(f"S{i}", "S", (f"b{i}", "e"), point=(0.5 * c, 0.5 * s, 1.0)))
    return Mechanism(f"{limbs}-PRS", "g", "e", tuple(joints))


def far_pivot() -> Mechanism:
    """A four-bar with one pivot at 1e300 and the others near the origin: finer than any analysis resolves."""
    m = mobility.load(MECHANISMS / "four_bar.yaml")
    joints = list(m.world_joints)
    joints[3] = dataclasses.replace(joints[3], point=(1e300, 0.0, 0.0))
    return m.replace(joints=tuple(joints), frames=())


def lone_far_pivot() -> Mechanism:
    """One hinge at 1e308 on every axis: a valid mechanism (1R) that no picture can hold (a drawing squares coordinates)."""
    return Mechanism("lone pivot", "a", "b", (Joint("j", "R", ("a", "b"), axis=(0.0, 0.0, 1.0), point=(1e308, 1e308, 1e308), actuated=True),))


THREE_PRS = mobility.load(MECHANISMS / "3prs.yaml")
PLANAR_3RRR = mobility.load(MECHANISMS / "planar_3rrr.yaml")

EXTREME: dict[str, Callable[[], Mechanism]] = {
    "3prs x 1e200": lambda: scaled(THREE_PRS, 1e200),
    "3prs x 1e-250": lambda: scaled(THREE_PRS, 1e-250),
    "planar 3-RRR x 1e-250": lambda: scaled(PLANAR_3RRR, 1e-250),
    "pivot at 1e300": far_pivot,
    "lone pivot at 1e308": lone_far_pivot,
}

LARGE: dict[str, Callable[[], Mechanism]] = {
    "ladder of 2,001 joints": lambda: ladder(1000),
    "180-joint parallel mechanism": lambda: prs(60),
}


# -- the commands -------------------------------------------------------------------------------


def sweep_range(m: Mechanism) -> str:
    """A small sweep of the first drivable joint: 5 degrees, or 1 % of the mechanism's size for a slider."""
    joint = next(j for j in m.joints if j.type in "RPHC")
    if joint.type != "P":
        return f"{joint.name}=0:5:3"
    from mobility.core.joint_screws import joint_screws

    return f"{joint.name}=0:{0.01 * joint_screws(m).normalisation.length!r}:3"


def commands(m: Mechanism, path: Path, out: Path) -> dict[str, list[str]]:
    """Every command and option under test, on the file ``path``, writing into the folder ``out``."""
    f = str(path)
    return {
        "analyze": ["analyze", "--json", f],
        "analyze --finite": ["analyze", "--finite", f],
        "check": ["check", "--json", f],
        "actuation": ["actuation", "--json", f],
        "actuation --enumerate": ["actuation", "--enumerate", "--json", f],
        "actuation --samples": ["actuation", "--samples", "2", "--json", f],
        "plot": ["plot", "--constraints", f, "-o", str(out / "picture.png"), "--dpi", "30"],
        "plot --graph": ["plot", "--graph", f, "-o", str(out / "graph.png"), "--dpi", "30"],
        "jacobian": ["jacobian", "--json", f],
        "sweep": ["sweep", f, "--vary", sweep_range(m), "--json", "--no-progress"],
        "view": ["view", f, "-o", str(out / "view.html")],
        "view --samples": ["view", "--samples", "2", f, "-o", str(out / "samples.html")],
        "convert": ["convert", f, "-o", str(out / "converted.yaml")],
    }


def run_cli(args: list[str]) -> tuple[int, str, str]:
    """``mobility ARGS`` in-process under the time guard; numpy warnings are errors (they would reach stderr)."""
    import warnings

    from mobility.cli import main

    out, err = io.StringIO(), io.StringIO()
    with time_bound(RUN_BOUND), contextlib.redirect_stdout(out), contextlib.redirect_stderr(err), warnings.catch_warnings():
        warnings.simplefilter("error", RuntimeWarning)
        try:
            status = main(args)
        except TookTooLong as exc:
            return -1, out.getvalue(), str(exc)
    return status, out.getvalue(), err.getvalue()


# -- what a run must end in -----------------------------------------------------------------------

NON_FINITE = re.compile(r"(?<![\w.])(nan|-?inf|NaN|-?Infinity)(?![\w.])")


def page_figure(html: str) -> Any:
    """The figure (data and layout) that a page of ``mobility view`` hands to plotly."""
    call = html.rindex("Plotly.newPlot(")
    text = html[html.index("[", call):]
    decoder = json.JSONDecoder()
    data, end = decoder.raw_decode(text)
    layout, _ = decoder.raw_decode(text[end:].lstrip(" ,\n"))
    return {"data": data, "layout": layout}


def written_numbers_are_finite(args: list[str]) -> str:
    """'' when the file a run wrote (picture, page, converted file) is there and its numbers are finite, else why not."""
    if "-o" not in args:
        return ""
    path = Path(args[args.index("-o") + 1])
    if not path.exists() or path.stat().st_size == 0:
        return f"{path.name} was not written"
    if path.suffix == ".html":
        figure = page_figure(path.read_text(encoding="utf-8"))
        return "" if finite_numbers(figure) and "NaN" not in json.dumps(figure) else f"{path.name}: a number of the figure is not finite"
    if path.suffix == ".yaml":
        back = mobility.load(path)  # what was written reads back
        numbers = [x for j in back.world_joints for v in (j.point, j.axis, j.normal) if v is not None for x in v]
        return "" if all(math.isfinite(x) for x in numbers) else f"{path.name}: a number is not finite"
    return ""


def verdict(args: list[str], status: int, out: str, err: str) -> str:
    """'' when the run ended as the contract says, else what went wrong (for the failure message)."""
    if status == 2 and args[0] == "check" and not err:  # check reports a bad file in its table, one line each
        rows = json.loads(out)["results"]
        return "" if all(r["status"] != "error" or "\n" not in r["message"] for r in rows) else "check: an error of several lines"
    if status == 2:
        return "" if err.count("\n") == 1 and err.startswith("mobility: ") else f"exit 2 but stderr is not one line: {err[:300]!r}"
    if status not in (0, 1):
        return f"exit {status}: {err.strip()[:300]}"
    noise = [line for line in err.splitlines() if not line.startswith(("mobility: note: ", "mobility: wrote "))]
    if noise:
        return f"exit {status} with stderr: {noise[0][:300]}"
    try:
        printed = json.loads(out)
    except ValueError:
        if NON_FINITE.search(out):
            return f"a non-finite number printed: {NON_FINITE.search(out).group(0)!r}"
    else:
        if not finite_numbers(printed):
            return "a non-finite number in the JSON printed"
    return written_numbers_are_finite(args)


def run_all(m: Mechanism, folder: Path) -> dict[str, tuple[int, str]]:
    """Write ``m`` to ``folder`` and run every command on it: ``{command: (exit status, what went wrong or '')}``."""
    path = folder / "mechanism.yaml"
    path.write_text(yaml_text(m), encoding="utf-8")
    outcome = {}
    for name, args in commands(m, path, folder).items():
        status, out, err = run_cli(args)
        outcome[name] = (status, verdict(args, status, out, err))
    return outcome


# -- the tests ------------------------------------------------------------------------------------


@pytest.mark.parametrize("case", sorted(EXTREME))
def test_every_command_at_an_extreme_scale_answers_or_refuses_in_one_line(case, tmp_path):
    outcome = run_all(EXTREME[case](), tmp_path)
    failures = {name: why for name, (_, why) in outcome.items() if why}
    assert not failures, failures
    refused = {name for name, (status, _) in outcome.items() if status == 2}
    if case == "pivot at 1e300":  # geometry finer than any analysis resolves: everything that analyses refuses it
        assert set(outcome) - refused <= {"convert"}
    elif case == "lone pivot at 1e308":  # analysed; drawn nowhere (too far out for a drawing's arithmetic)
        assert refused == {"plot", "view", "view --samples"}, refused
    else:  # a valid mechanism at any scale: every command answers (convert: when its file can hold the numbers)
        assert refused <= ({"convert"} if "1e-250" in case else set()), refused


def child_main(case: str, folder: str) -> None:
    """In the child process: cap the address space, run every command on the large case, print the outcomes as JSON."""
    resource.setrlimit(resource.RLIMIT_AS, (MEMORY_CAP, MEMORY_CAP))
    outcome = run_all(LARGE[case](), Path(folder))
    peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss * 1024
    print(json.dumps({"outcome": outcome, "peak_bytes": peak}))


@pytest.mark.parametrize("case", sorted(LARGE))
def test_every_command_on_a_large_mechanism_answers_or_refuses_in_bounded_memory(case, tmp_path):
    env = dict(os.environ, MPLBACKEND="Agg", OPENBLAS_NUM_THREADS="1", OMP_NUM_THREADS="1")
    done = subprocess.run([sys.executable, __file__, case, str(tmp_path)], capture_output=True, text=True, timeout=600, env=env, cwd=ROOT)
    assert done.returncode == 0, done.stderr[-2000:]
    report = json.loads(done.stdout.splitlines()[-1])
    outcome = {name: tuple(v) for name, v in report["outcome"].items()}
    failures = {name: why for name, (_, why) in outcome.items() if why}
    assert not failures, failures
    refused = {name for name, (status, _) in outcome.items() if status == 2}
    # what may refuse, by its own limit: finite motion beyond 50 joints, enumeration beyond 200 (or its
    # count of combinations), moving beyond 300; a ladder has no serial limbs for a Jacobian
    allowed = {"analyze --finite", "actuation --enumerate", "actuation --samples", "sweep", "view --samples"} if "ladder" in case else {"analyze --finite", "actuation --enumerate"}
    assert refused <= allowed | ({"jacobian"} if "ladder" in case else set()), refused
    assert report["peak_bytes"] < MEMORY_CAP


def test_a_command_beyond_its_limit_names_the_limit_and_its_variable(tmp_path, monkeypatch):
    path = tmp_path / "prs.yaml"
    path.write_text(yaml_text(prs(4)), encoding="utf-8")  # 12 joints
    status, out, err = run_cli(["analyze", "--finite", str(path)])
    assert status == 0 and "full-cycle" in out, err  # within the default limit of 50
    monkeypatch.setenv("MOBILITY_MAX_FINITE_JOINTS", "11")
    status, out, err = run_cli(["analyze", "--finite", str(path)])
    assert (status, out) == (2, "") and err.count("\n") == 1
    assert f"mobility: {path}: joints: 12 joints are more than the limit of 11 for --finite (set MOBILITY_MAX_FINITE_JOINTS to raise it)" in err
    monkeypatch.setenv("MOBILITY_MAX_FINITE_JOINTS", "12")
    status, out, err = run_cli(["analyze", "--finite", str(path)])
    assert status == 0 and "full-cycle" in out, err
    monkeypatch.setenv("MOBILITY_MAX_MOVING_JOINTS", "11")
    for args in (["sweep", str(path), "--vary", "R0=0:1:2"], ["view", "--samples", "1", str(path), "-o", str(tmp_path / "v.html")], ["actuation", "--samples", "1", str(path)]):
        status, out, err = run_cli(args)
        assert status == 2 and "more than the limit of 11" in err and "MOBILITY_MAX_MOVING_JOINTS" in err, (args, err)


def test_an_enumeration_too_large_is_refused_with_its_exact_count_before_any_is_listed(tmp_path, monkeypatch):
    # two candidates (P, R) in each of 70 limbs, 3 DOF: one in each of 3 limbs, C(70, 3) * 2**3 combinations,
    # counted limb by limb (the 54,740 choices of limbs are never listed); once 2**70, one in every limb
    monkeypatch.setenv("MOBILITY_MAX_ENUMERATED_JOINTS", "1000")
    path = tmp_path / "prs.yaml"
    path.write_text(yaml_text(prs(70)), encoding="utf-8")
    status, out, err = run_cli(["actuation", "--enumerate", str(path)])
    assert status == 2 and f"mobility: {math.comb(70, 3) * 2**3} combinations to try" in err and err.count("\n") == 1


# -- the answers at scale, by a second route ------------------------------------------------------


def jacobian_parts(m: Mechanism) -> tuple[np.ndarray, np.ndarray, np.ndarray, list[str]]:
    from mobility.jacobians import jacobian

    j = jacobian(m)
    kinds = [m.joint(label.split(".")[0]).type for label in j.actuated]
    # the constraint rows in normalised terms, [f; m / L], each over its largest entry (nothing squared)
    normalised = j.constraint_wrenches / np.array([1, 1, 1, j.length, j.length, j.length])
    normalised /= np.abs(normalised).max(axis=1)[:, None]
    return j.actuation_wrenches, normalised, j.twist_map, kinds


def unscaled_wrenches(rows: np.ndarray, factor: float, per_length: list[bool]) -> np.ndarray:
    """Wrench rows of a mechanism scaled by ``factor`` brought back to scale 1 (moments over ``factor``; a wrench per unit angle times it)."""
    out = rows.copy()
    out[:, 3:] /= factor
    return out * np.where(per_length, 1.0, factor)[:, None]


@settings(max_examples=25, deadline=None, derandomize=True)
@given(exponent=st.integers(-300, 300), name=st.sampled_from(["3prs", "planar_3rrr", "6ups", "tricept"]))
def test_the_jacobian_of_a_scaled_mechanism_is_the_jacobian_scaled(exponent, name):
    from mobility.core.screws import same_subspace

    m = mobility.load(MECHANISMS / f"{name}.yaml")
    factor = 10.0**exponent
    act, con, twists, kinds = jacobian_parts(m)
    act_k, con_k, twists_k, _ = jacobian_parts(scaled(m, factor))
    per_length = [k == "P" for k in kinds]
    # actuation wrenches and the twists per unit input rate are unique: equal after unscaling
    assert np.allclose(unscaled_wrenches(act_k, factor, per_length), act, rtol=1e-8, atol=1e-9 * np.abs(act).max())
    back = twists_k.copy()
    back[3:] /= factor  # velocities are lengths per time
    back *= np.where(per_length, factor, 1.0)[None, :]  # per unit length of a slider's rate
    assert np.allclose(back, twists, rtol=1e-8, atol=1e-9 * np.abs(twists).max())
    # the constraint wrenches are a basis of a subspace: the same subspace (in normalised terms, scale-free)
    assert same_subspace(con_k.T, con.T)


@pytest.mark.parametrize("factor", [1e200, 1e-250])
def test_the_jacobian_command_prints_the_same_digits_scaled(tmp_path, factor):
    from mobility.core.joint_screws import joint_screws

    texts = {}
    for k in (1.0, factor):
        path = tmp_path / f"m{k}.yaml"
        path.write_text(yaml_text(scaled(PLANAR_3RRR, k)), encoding="utf-8")
        status, out, err = run_cli(["jacobian", "--json", str(path)])
        assert status == 0 and err == "", err
        texts[k] = json.loads(out)
    one, big = texts[1.0], texts[factor]
    assert one["condition"] == pytest.approx(big["condition"], rel=1e-9) and one["rank"] == big["rank"] == 6
    # the actuation rows of J: revolute inputs, so [m; f] becomes [m; f / k]
    for row, row_k in zip(one["matrix"][:3], big["matrix"][:3]):
        assert np.allclose(np.array(row_k) * [1, 1, 1, factor, factor, factor], row, rtol=1e-8, atol=1e-9)
    # each actuation axis passes through the same point, scaled
    for axis, axis_k in zip(one["actuation_axes"], big["actuation_axes"]):
        assert axis["kind"] == axis_k["kind"] == "force"
        assert np.allclose(np.array(axis_k["point"]) / factor, axis["point"], rtol=1e-8, atol=1e-9 * joint_screws(PLANAR_3RRR).normalisation.length)


@pytest.mark.parametrize("factor", [1e200, 1e-250, 2e307 / 40.0])
def test_the_picture_of_a_scaled_mechanism_is_the_same_picture(factor):
    import matplotlib

    matplotlib.use("Agg")
    from mobility.report.plotting import plot_mechanism, sketch

    def rotation_axes(m: Mechanism) -> tuple[dict[str, np.ndarray], float]:
        fig = plot_mechanism(m, constraints=True, views=[(30, 40)])
        lines = {line.get_gid(): np.column_stack(line.get_data_3d()) for line in fig.axes[0].get_lines() if (line.get_gid() or "").startswith(("mobility:rotation-axis", "mobility:force:"))}
        return lines, sketch(m).scale

    plain, one = rotation_axes(THREE_PRS)
    big, scale = rotation_axes(scaled(THREE_PRS, factor))
    assert one == 1.0 and 0.1 < sketch(scaled(THREE_PRS, factor)).size < 10.0  # the plain one in its file's numbers, the scaled one near 1
    assert plain.keys() == big.keys() and len(plain) >= 4
    for gid, line in plain.items():  # the same lines, in drawing units: the file's times the drawing scale
        assert np.allclose(big[gid] / (factor * scale), line, rtol=1e-8, atol=1e-9), gid


def test_the_view_of_a_scaled_mechanism_labels_its_axes_in_the_file_units():
    from mobility.view import mechanism_view

    plain = mechanism_view(THREE_PRS).figure_dict
    view = mechanism_view(scaled(THREE_PRS, 1e-250))
    big, per_drawn = view.figure_dict, 1.0 / view.scenes[0].scale  # file units per drawing unit
    assert "tickvals" not in plain["layout"]["scene"]["xaxis"]  # an everyday size: plotly's own ticks
    for name in ("xaxis", "yaxis", "zaxis"):
        axis = big["layout"]["scene"][name]
        lo, hi = axis["range"]
        assert all(lo <= v <= hi for v in axis["tickvals"]) and len(axis["tickvals"]) >= 3
        drawn, shown = np.array(axis["tickvals"]), np.array([float(t) for t in axis["ticktext"]])
        ratio = shown[shown != 0] / drawn[shown != 0]  # one factor from drawing units to the file's
        assert np.allclose(ratio, per_drawn, rtol=1e-6)  # each tick's text is the file's value where it is drawn
    traces = [t for t in big["data"] if t["meta"]["key"] == "R1" and "x" in t]
    plain_traces = [t for t in plain["data"] if t["meta"]["key"] == "R1" and "x" in t]
    assert np.allclose(np.array(traces[0]["x"], dtype=float) * per_drawn / 1e-250, np.array(plain_traces[0]["x"], dtype=float), rtol=1e-5, atol=1e-6, equal_nan=True)  # None: a break in the line



@pytest.mark.parametrize("factor, offset", [(1.0, 3e7), (1e-6, 1000.0)])
def test_the_view_of_a_mechanism_far_from_the_origin_is_drawn_about_its_middle(factor, offset):
    # With absolute coordinates written to 7 digits, a 3-PRS a millionth of its size, moved 1000 mm away,
    # was drawn with two distinct x values (and at 3e7 mm its axis lines were 1 % of its size off)
    from mobility.view import mechanism_view

    def moved(m: Mechanism) -> Mechanism:
        return m.replace(joints=tuple(dataclasses.replace(j, point=(j.point[0] + offset, j.point[1], j.point[2])) if j.point is not None else j
                                      for j in m.world_joints), frames=())

    near, far = scaled(THREE_PRS, factor), moved(scaled(THREE_PRS, factor))
    plain, view = mechanism_view(near).figure_dict, mechanism_view(far).figure_dict
    per_drawn = 1.0 / mechanism_view(far).scenes[0].scale  # file units per drawing unit (the same near and far)
    lo, hi = plain["layout"]["scene"]["xaxis"]["range"]
    middle, width = 0.5 * (lo + hi), hi - lo  # the near scene's middle: where the far one's is drawn from
    compared = 0
    for mine, theirs in zip(view["data"], plain["data"]):  # the same glyphs, drawn the same about the scene's middle
        assert mine["meta"] == theirs["meta"]
        if "x" in mine and mine["meta"]["key"] in ("R1", "W2", "T1"):
            x, x0 = np.array(mine["x"], dtype=float) + middle, np.array(theirs["x"], dtype=float)
            assert np.allclose(x, x0, rtol=0, atol=1e-6 * width, equal_nan=True), mine["meta"]
            compared += 1
    assert compared >= 3
    axis = view["layout"]["scene"]["xaxis"]
    shown = np.array([float(t) for t in axis["ticktext"]])
    assert len(set(axis["ticktext"])) == len(shown) >= 3  # ticks told apart
    file_x = (np.array(axis["tickvals"]) + middle) * per_drawn + offset  # the file's x where each tick is drawn
    assert np.allclose(shown, file_x, rtol=1e-12, atol=1e-9 * width * per_drawn)


if __name__ == "__main__":  # the child process of the large cases
    child_main(sys.argv[1], sys.argv[2])
