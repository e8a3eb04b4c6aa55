"""Sweeps: every batched answer equals the one-pose routes, and the classic singularities are found.

Each pose a sweep reports is rebuilt as a mechanism
(:meth:`SweepResult.mechanism_at`, i.e. :meth:`Kinematics.mechanism_at`) and
checked against :func:`mobility.analyze`, the loop-closure route
(:func:`mobility.loop_closure`), the single-pose loop residual
(:meth:`Kinematics.residual`) and :func:`mobility.check_actuation`.
"""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import mobility
from mobility.core.joint_screws import joint_screws
from mobility.core.kinematics import kinematics
from mobility.core.tolerance import ROW_BY_ROW, characteristic_scale, characteristic_scales, decide_few, decide_rank, decide_ranks
from mobility.core.transforms import displacement_log, twist_exp
from mobility.errors import MechanismError, RequestError
from mobility.sweeps import SweepResult, plan_grid, sweep
from mobility.core.transforms import displacement_logs, rotation_logs
from mobility.core.screw_systems import Margins, analyse_poses
from mobility.core.topology import decompose
from mobility.sweeps.steps import Drive, residuals
from mobility.sweeps.posed_screws import posed_screws
from mobility.report.sweep import sweep_csv, sweep_json, sweep_summary

from conftest import MECHANISMS
from guards import time_bound
from builders import flat_3rps

RNG_SEED = 20240611


def load(name: str) -> mobility.Mechanism:
    return mobility.load(MECHANISMS / f"{name}.yaml")


def assert_pose_matches_one_pose_routes(result: SweepResult, i: int) -> None:
    """Row ``i`` of a sweep against analyze, loop closure, the loop residual and check_actuation of the rebuilt pose."""
    pose = result.mechanism_at(i)
    direct = mobility.analyze(pose, tol=result.tolerance)
    assert (int(result.dof[i]), result.pattern[i], int(result.mobility[i])) == (direct.dof, direct.pattern, direct.mobility)
    assert bool(result.near_singular[i]) == direct.margin.near_singular
    assert result.smallest_kept[i] == pytest.approx(direct.margin.smallest_kept, rel=1e-6, abs=1e-12)
    lc = mobility.loop_closure(pose, result.tolerance)
    assert (lc.mobility, lc.end_effector_twists.shape[1]) == (direct.mobility, direct.dof)
    assert np.abs(kinematics(result.mechanism).residual(result.q[i])).max(initial=0.0) <= result.tolerance.closure
    if result.actuated:
        check = mobility.check_actuation(pose, list(result.actuated), tol=result.tolerance)
        assert result.verdict[i] == check.verdict
        assert result.conditioning[i] == pytest.approx(check.conditioning, rel=1e-6, abs=1e-8)  # round-off grows near a singularity


def random_rows(result: SweepResult, count: int, seed: int = RNG_SEED) -> np.ndarray:
    rows = np.flatnonzero(result.assembled)
    return np.random.default_rng(seed).choice(rows, size=min(count, rows.size), replace=False)


# --- the tolerance policy over stacks --------------------------------------------------------


def test_decide_ranks_is_decide_rank_row_by_row():
    rng = np.random.default_rng(RNG_SEED)
    s = -np.sort(-np.abs(rng.standard_normal((300, 6))) * 10.0 ** rng.integers(-14, 3, size=(300, 6)), axis=1)
    s[::7, 2:] = 0.0
    counts = rng.integers(0, 7, size=300)
    batch = decide_ranks(s, counts=counts)
    for row, count, r, kept, dropped in zip(s, counts, *batch):
        assert tuple(decide_rank(row[:count])) == (r, kept, dropped)


def test_a_few_rows_are_decided_as_a_long_stack_is():
    # up to ROW_BY_ROW rows (one pose's stacks) go row by row in Python (decide_few): the numbers and types of the vectorised route
    rng = np.random.default_rng(RNG_SEED + 1)
    s = -np.sort(-np.abs(rng.standard_normal((301, 6))) * 10.0 ** rng.integers(-14, 3, size=(301, 6)), axis=1)
    s[::5, 3:] = 0.0
    counts = rng.integers(0, 7, size=301)
    batch = decide_ranks(s, counts=counts)
    for start in range(0, 301, ROW_BY_ROW):
        rows = slice(start, start + ROW_BY_ROW)
        few = decide_ranks(s[rows], counts=counts[rows])
        assert [x.tolist() for x in few] == [x[rows].tolist() for x in batch]
        assert [x.dtype for x in few] == [x.dtype for x in batch]
        assert decide_few(s[rows], counts=counts[rows]) == tuple(tuple(x[rows].tolist()) for x in batch)
    same = decide_ranks(s, counts=4)
    assert decide_few(s[:3], counts=4) == tuple(tuple(x[:3].tolist()) for x in same)
    assert decide_few(s[:0]) == ((), (), ()) and decide_ranks(s[:0]).rank.dtype == batch.rank.dtype


def test_the_margins_of_one_pose_are_those_of_a_stack_of_one():
    rng = np.random.default_rng(RNG_SEED)
    one, many = Margins(1), Margins(1)
    every_kept, every_dropped = [], []
    for size in (3, 1, 2, 1):
        kept, dropped = rng.random(size), rng.random(size) * 1e-12
        one.add(tuple(kept.tolist()), tuple(dropped.tolist()))  # as decide_few gives them
        many.add(kept, dropped)
        every_kept += kept.tolist()
        every_dropped += dropped.tolist()
        assert one.smallest_kept.tolist() == many.smallest_kept.tolist() == [min(every_kept)]
        assert one.largest_dropped.tolist() == many.largest_dropped.tolist() == [max(every_dropped)]
    two = Margins(2)
    two.add(np.array([0.5, 0.9, 0.3, 0.8]), np.array([0.0, 1e-13, 2e-13, 0.0]))  # two stacks of the two poses
    assert two.smallest_kept.tolist() == [0.3, 0.8] and two.largest_dropped.tolist() == [2e-13, 1e-13]


def test_characteristic_scales_is_characteristic_scale_pose_by_pose():
    rng = np.random.default_rng(RNG_SEED)
    points = rng.standard_normal((20, 5, 3)) * 40.0
    points[3] = points[3, :1]  # all points at one place: the other length is used
    centres, lengths = characteristic_scales(points, np.array([2.5]))
    for p, c, length in zip(points, centres, lengths):
        c1, l1 = characteristic_scale(p, np.array([2.5]))
        assert np.allclose(c, c1, rtol=1e-14, atol=1e-12) and length == pytest.approx(l1, rel=1e-14)


def test_batched_logs_invert_exponentials():
    from scipy.spatial.transform import Rotation

    rng = np.random.default_rng(RNG_SEED)
    axes = rng.standard_normal((50, 3))
    w = axes / np.linalg.norm(axes, axis=1)[:, None] * rng.choice([1e-9, 0.3, 2.0, 3.0, 3.1], size=(50, 1))
    assert np.allclose(rotation_logs(Rotation.from_rotvec(w).as_matrix()), w, rtol=1e-9, atol=1e-15)
    x = np.concatenate([w, rng.standard_normal((50, 3))], axis=1)
    g = np.array([twist_exp(t) for t in x])
    assert np.allclose(displacement_logs(g), [displacement_log(gi) for gi in g], rtol=1e-12, atol=1e-13)


# --- the batched kinematics and screw systems against the one-pose ones ------------------------


@pytest.mark.parametrize("name", ["3prs", "stephenson_six_bar", "planar_5r", "bennett", "6ups", "xy_sprint_hybrid"])
def test_batched_analysis_equals_analyze_on_random_closed_poses(name):
    m = load(name)
    kin = kinematics(m)
    rng = np.random.default_rng(RNG_SEED)
    qs = [np.zeros(kin.variable_count)]
    _, null = kin.rank_decision(np.zeros(kin.variable_count))
    for _ in range(5):
        d = null @ rng.standard_normal(null.shape[1])
        d *= 0.25 / np.linalg.norm(d)
        closed = kin.close(d, constraints=(d[None], np.array([d @ d])))
        if closed.converged:
            qs.append(closed.q)
    q = np.array(qs)
    bk = kinematics(m)
    assert np.allclose(bk.residual(q), [kin.residual(x) for x in q], atol=1e-13)
    moved = bk.link_displacements(q)
    for k, x in enumerate(q):
        for link, g in kin.link_displacements(x).items():
            assert np.allclose(moved[link][k], g, atol=1e-13)
    posed = posed_screws(bk, q)
    answers = analyse_poses(decompose(m), posed.twists, posed.offsets)
    for k, x in enumerate(q):
        direct = mobility.analyze(kin.mechanism_at(x))
        assert (answers.dof[k], answers.pattern[k], answers.mobility[k]) == (direct.dof, direct.pattern, direct.mobility)
        assert answers.smallest_kept[k] == pytest.approx(direct.margin.smallest_kept, rel=1e-6)


def test_posed_twists_at_the_given_pose_are_the_joint_screws():
    for name in ("3prs", "tricept", "h4", "4puu"):
        m = load(name)
        posed = posed_screws(kinematics(m), np.zeros((1, kinematics(m).variable_count)))
        js = joint_screws(m)
        assert np.allclose(posed.twists[0], js.twists, atol=1e-14)
        assert np.allclose(posed.centres[0], js.normalisation.centre) and posed.lengths[0] == pytest.approx(js.normalisation.length)


# --- what the issue asks the sweeps to find -------------------------------------------------------------


def test_parallelogram_full_turn_has_mobility_two_exactly_at_the_folded_poses():
    m = load("parallelogram")  # crank at phi = 60 deg in the file: folded at phi = 180 and 360
    r = sweep(m, ["O1=0:360:361"])
    assert r.assembled.all() and r.residual.max() <= r.tolerance.closure
    folded = np.flatnonzero(r.mobility == 2)
    assert r.values[folded, 0].tolist() == [120.0, 300.0]
    assert set(r.mobility[np.setdiff1d(np.arange(361), folded)].tolist()) == {1}
    assert [p.values for p in r.singular] == [(120.0,), (300.0,)]
    assert sorted({(int(a), int(b)) for a, b, _ in r.changes}) == [(119, 120), (120, 121), (299, 300), (300, 301)]
    for i in (119, 120, 121, 300):
        assert_pose_matches_one_pose_routes(r, i)
    # the continuation stays on the parallelogram branch through both change points: cranks parallel
    for i in (150, 200, 340):
        pose = r.mechanism_at(i)
        crank1 = np.subtract(pose.joint("A1").point, pose.joint("O1").point)
        crank2 = np.subtract(pose.joint("A2").point, pose.joint("O2").point)
        assert np.allclose(crank1, crank2, atol=1e-9)
        phi = math.degrees(math.atan2(crank1[1], crank1[0])) % 360.0
        assert phi == pytest.approx((60.0 + r.values[i, 0]) % 360.0, abs=1e-9)


def test_the_way_to_a_grid_next_to_a_change_point_keeps_the_files_branch():
    # the grid's first point is reached from the file's pose (60 deg) by the same predictor as the grid's lines, so it
    # arrives just short of the fold (180 deg) on the parallelogram branch, not on the anti-parallelogram one
    r = sweep(load("parallelogram"), ["O1=119.9787:119.99:2"])
    assert r.assembled.all()
    assert r.pattern.tolist()[0] == "1T"
    pose = r.mechanism_at(0)
    crank1 = np.subtract(pose.joint("A1").point, pose.joint("O1").point)
    crank2 = np.subtract(pose.joint("A2").point, pose.joint("O2").point)
    assert np.allclose(crank1, crank2, atol=1e-9)


def test_three_prs_stays_three_dof_1t2r_over_a_grid_of_its_sliders():
    r = sweep(load("3prs"), ["P1=-30:30:7", "P2=-30:30:7", "P3=-30:30:7"])
    assert r.assembled.all()
    assert r.counts() == {(3, "1T2R", 3): 343}
    assert r.verdict_counts() == {"valid": 343} and r.singular == () and len(r.changes) == 0
    for i in random_rows(r, 8):
        assert_pose_matches_one_pose_routes(r, i)
    # the sliders are where the grid put them: P1 = -30 mm is a slide of -30 mm along the guide
    i = int(np.ravel_multi_index((0, 3, 6), r.shape))
    pose, given = r.mechanism_at(i), r.mechanism
    for name, expect in (("R1", -30.0), ("R2", 0.0), ("R3", 30.0)):
        moved = np.subtract(pose.joint(name).point, given.world_joints[[j.name for j in given.joints].index(name)].point)
        assert np.allclose(moved, [0.0, 0.0, expect], atol=1e-9)


@pytest.mark.parametrize("name, joint, singular", [("4puu_singular", "P1", "3T1R"), ("3upu_singular", "P1", "3T1R")])
def test_constraint_singular_poses_are_found(name, joint, singular):
    r = sweep(load(name), [f"{joint}=-20:20:9"])
    assert r.assembled.all()
    assert [p.values for p in r.singular] == [(0.0,)]
    p = r.singular[0]
    assert (p.dof, p.pattern, p.mobility) == (4, singular, 4)
    assert "gains 1 freedom" in p.reasons[0]
    others = np.flatnonzero(r.values[:, 0] != 0.0)
    assert set(r.dof[others].tolist()) == {3}
    for i in (int(p.index), int(others[0]), int(others[-1])):
        assert_pose_matches_one_pose_routes(r, i)


def test_three_upu_margin_falls_to_the_singular_pose():
    r = sweep(load("3upu_singular"), ["P3=-12:12:7"])
    margin = r.smallest_kept
    centre = int(np.flatnonzero(r.values[:, 0] == 0.0)[0])
    assert np.all(np.diff(margin[:centre]) < 0) and np.all(np.diff(margin[centre + 1 :]) > 0)  # the margin shrinks towards it


def test_five_bar_map_shows_its_type_two_singularity():
    m = load("planar_5r")  # distal links at right angles in the file: aligned at P = +-90 deg
    r = sweep(m, ["A1=-10:30:9", "P=60:100:9"])
    assert r.actuated == ("A1", "A2")
    flagged = [p for p in r.singular]
    assert flagged and all(p.values[1] == 90.0 and p.verdict == "actuation-singular" for p in flagged)
    assert {v for v, ok, p in zip(r.verdict, r.assembled, r.values[:, 1]) if ok and p != 90.0} == {"valid"}
    for p in flagged:
        pose = r.mechanism_at(p.index)
        check = mobility.check_actuation(pose)
        assert check.verdict == "actuation-singular" and check.conditioning == 0.0
        assert mobility.actuation.locked_dof(pose, ["A1", "A2"]) == 1  # second route: inputs locked, the end effector still moves
        direct = mobility.analyze(pose)
        assert (direct.dof, direct.mobility) == (2, 2)
    for i in random_rows(r, 6):
        assert_pose_matches_one_pose_routes(r, i)
    kappa = r.grid("conditioning")
    column = list(r.axes[1].values).index(90.0)
    assert np.nanmax(kappa[:, column]) == 0.0 and np.nanmin(np.delete(kappa, column, axis=1)) > 0.0


def test_pose_coordinates_drive_the_end_effector():
    m = load("3rps")
    r = sweep(m, ["z=-20:20:5", "rx=-6:6:3"])
    assert r.assembled.all() and r.counts() == {(3, "1T2R", 3): 15}
    given = np.array([j.point for j in m.world_joints if m.end_effector in j.links])
    for i in random_rows(r, 5):
        assert_pose_matches_one_pose_routes(r, i)
        pose = r.mechanism_at(i)
        moved = np.array([j.point for j in pose.world_joints if m.end_effector in j.links])
        z, rx = r.values[i]
        assert (moved.mean(axis=0) - given.mean(axis=0))[2] == pytest.approx(z, abs=1e-9)
        # the rotation taking the platform's points to their new places (Kabsch), as a rotation vector
        a, b = given - given.mean(axis=0), moved - moved.mean(axis=0)
        u, _, vt = np.linalg.svd(b.T @ a)
        rot = u @ np.diag([1.0, 1.0, np.linalg.det(u @ vt)]) @ vt
        from scipy.spatial.transform import Rotation

        assert math.degrees(Rotation.from_matrix(rot).as_rotvec()[0]) == pytest.approx(rx, abs=1e-7)


def test_unreachable_poses_are_rows_not_assembled():
    r = sweep(load("planar_5r"), ["A1=-40:40:9", "A2=-40:40:9"])
    assert not r.assembled.all() and r.assembled.any()
    missing = np.flatnonzero(~r.assembled)
    assert (r.dof[missing] == -1).all() and (r.pattern[missing] == "").all() and np.isnan(r.smallest_kept[missing]).all()
    assert (r.residual[missing] > r.tolerance.closure).all()
    assert len(r.values) == 81  # never dropped
    for i in random_rows(r, 4):
        assert_pose_matches_one_pose_routes(r, i)


def test_a_serial_arm_without_loops_is_swept_too():
    m = load("scara")
    names = [j.name for j in m.joints if j.type in "RPHC"][:2]
    r = sweep(m, [f"{names[0]}=0:90:4", f"{names[1]}=-45:45:3"], actuated=[])
    assert r.assembled.all() and not r.actuated
    for i in random_rows(r, 4):
        assert_pose_matches_one_pose_routes(r, i)


# --- angles that wrap ---------------------------------------------------------------------------------


def four_bar_reach(m: mobility.Mechanism):
    """Whether the four-bar assembles at a crank displacement (degrees), from its link lengths alone.

    The crank AB turns about A; the dyad B-C-D closes when the distance BD lies between the difference and the
    sum of the coupler BC and the rocker CD.
    """
    a, b, c, d = (np.array(m.joint(name).point[:2], dtype=float) for name in "ABCD")
    crank, coupler, rocker, ground = (np.linalg.norm(u - v) for u, v in ((b, a), (c, b), (d, c), (d, a)))
    start = math.atan2(*(b - a)[::-1]) - math.atan2(*(d - a)[::-1])  # the crank's angle from AD in the file

    def reachable(displacement: float) -> bool:
        theta = start + math.radians(displacement)
        bd = math.sqrt(crank**2 + ground**2 - 2.0 * crank * ground * math.cos(theta))
        return abs(coupler - rocker) < bd < coupler + rocker

    return reachable


@pytest.mark.parametrize("vary", ["A=0:360:361", "A=-180:180:361", "A=-360:360:721", "A=0:359:360", "A=100:460:73", "A=200:350:16"])
def test_a_crank_that_cannot_turn_fully_is_assembled_wherever_it_reaches(vary):
    m = load("four_bar")  # crank at 63.4 deg from the ground line; it reaches -160.8 .. +34.0 deg from there
    r = sweep(m, [vary])
    reachable = four_bar_reach(m)
    assert r.assembled.tolist() == [reachable(v) for v in r.values[:, 0]]
    for i in random_rows(r, 3):
        assert_pose_matches_one_pose_routes(r, i)


def test_a_sweep_result_shows_itself_in_one_line():
    r = sweep(load("3prs"), ["P1=-20:20:31", "P2=-20:20:31"])
    assert repr(r).startswith("SweepResult('3-PRS parallel head (Sprint Z3), symmetric pose', 961 poses over P1 x P2, 961 assembled, regular: DOF 3 1T2R mobility 3 valid")
    assert "\n" not in repr(r) and len(repr(r)) < 200


@pytest.mark.parametrize("vary", ["O1=119.99:120.01:3", "O1=119.99:119.99:1", "O1=-60.01:-59.99:3", "O1=299.99:300.01:3"])
def test_the_pattern_next_to_a_change_point_does_not_depend_on_the_grid(vary):
    r = sweep(load("parallelogram"), [vary])  # 0.01 deg from a fold: round-off of a float64 closure alone made this 1R
    off = np.abs(np.abs(((r.values[:, 0] - 120.0) + 90.0) % 180.0 - 90.0)) > 1e-6
    assert r.pattern[off].tolist() == ["1T"] * int(off.sum()) and not r.near_singular[off].any()
    assert r.pattern[~off].tolist() == ["1T1R"] * int((~off).sum())
    for i in np.flatnonzero(off):
        assert mobility.analyze(r.mechanism_at(i)).pattern == "1T"


def test_a_point_not_assembled_has_no_mechanism():
    r = sweep(load("four_bar"), ["A=0:360:13"])
    missing = int(np.flatnonzero(~r.assembled)[0])
    with pytest.raises(RequestError, match=rf"grid point {missing} \(A=[0-9.]+\) was not assembled"):
        r.mechanism_at(missing)
    with pytest.raises(RequestError, match="expected a grid point index in 0..12"):
        r.mechanism_at(13)
    assert mobility.analyze(r.mechanism_at(0)).pattern == r.pattern[0]


def test_dead_centres_of_a_slider_crank_are_singular_poses():
    r = sweep(load("slider_crank"), ["O=-180:180:13"])
    dead = [p for p in r.singular]
    assert [p.values for p in dead] == [(-60.0,), (120.0,)]  # crank and rod in line
    assert all(p.dof == 0 and p.mobility == 1 and "dead point" in p.reasons[0] for p in dead)
    for p in dead:  # the end effector is instantaneously locked there, the crank still turns
        one = mobility.analyze(r.mechanism_at(p.index))
        assert (one.dof, one.mobility) == (0, 1)


def test_angles_a_turn_apart_are_one_joint_state():
    m = load("four_bar")
    up, centred = sweep(m, ["A=0:360:361"]), sweep(m, ["A=-180:180:361"])
    turns = [{float(v) % 360.0 for v in r.values[r.assembled, 0]} for r in (up, centred)]
    assert turns[0] == turns[1] and len(turns[0]) == 194  # -160 .. 33
    assert up.assembled[[0, 199, 200, 360]].tolist() == [True, False, True, True]
    crank = kinematics(m).variables_of("A").start
    for a, b in ((300, 120), (360, 180), (200, 20)):  # 300 deg is -60 deg, 360 is 0, 200 is -160
        assert up.q[a, crank] == pytest.approx(centred.q[b, crank], abs=1e-12)  # solved once, near the file's pose
        assert abs(up.q[a, crank]) <= math.pi and (math.degrees(up.q[a, crank]) - up.values[a, 0]) % 360.0 == pytest.approx(0.0, abs=1e-9)
        for joint in "BC":
            assert np.allclose(up.mechanism_at(a).joint(joint).point, centred.mechanism_at(b).joint(joint).point, atol=1e-9)
    assert up.counts() == {(1, "1R", 1): 195} and up.residual[up.assembled].max() <= up.tolerance.closure


def test_a_map_of_two_full_turns_assembles_every_pose_the_five_bar_reaches():
    m = load("planar_5r")
    a1, b1, p, b2, a2 = (np.array(m.joint(name).point[:2], dtype=float) for name in ("A1", "B1", "P", "B2", "A2"))
    reach = np.linalg.norm(p - b1) + np.linalg.norm(b2 - p)  # the two distal links, stretched

    def crank_end(centre, end, displacement):  # A2 joins proximal2 to the ground: its angle turns the other way
        angle = math.atan2(*(end - centre)[::-1]) + displacement
        return centre + np.linalg.norm(end - centre) * np.array([math.cos(angle), math.sin(angle)])

    r = sweep(m, ["A1=0:360:19", "A2=0:360:19"])
    expected = [np.linalg.norm(crank_end(a2, b2, -math.radians(v2)) - crank_end(a1, b1, math.radians(v1))) < reach for v1, v2 in r.values]
    assert r.assembled.tolist() == expected and sum(expected) == 316
    for i in random_rows(r, 4):
        assert_pose_matches_one_pose_routes(r, i)


def test_angles_many_turns_away_are_solved_near_the_file_pose_without_losing_digits():
    m = load("four_bar")
    far, near = sweep(m, ["A=500000:500000:1"]), sweep(m, ["A=-40:-40:1"])  # 500000 deg is 1389 turns less 40 deg
    assert far.assembled.all() and np.allclose(far.q, near.q, atol=1e-12) and far.values[0, 0] == 500000.0
    both = sweep(m, ["A=3.6e6:0:2"])  # ten thousand turns, and the file's pose
    assert both.assembled.all() and np.array_equal(both.q[0], both.q[1]) and both.residual.max() <= both.tolerance.closure
    assert both.counts() == {(1, "1R", 1): 2}


@pytest.mark.parametrize(
    "name, vary",
    [("parallelogram", "O1=100:140:4001"), ("parallelogram", "O1=0:360:7201"), ("four_bar", "A=20:40:4001"), ("parallelogram_change_point", "A=-30:30:4001")],
)
def test_a_long_line_solved_in_two_levels_gives_the_one_level_answers(monkeypatch, name, vary):
    """A 1-D sweep of thousands of points: every k-th point first, then the pieces between, all together (continuation._leg)."""
    from mobility.sweeps import continuation

    m = load(name)
    calls = []
    stride = continuation._coarse_stride
    monkeypatch.setattr(continuation, "_coarse_stride", lambda *a: calls.append(stride(*a)) or calls[-1])
    two = sweep(m, [vary])
    assert max(calls) >= 8  # the two-level path was taken
    monkeypatch.setattr(continuation, "TWO_LEVEL_LINES", 10**12)
    one = sweep(m, [vary])
    for column in ("assembled", "dof", "pattern", "mobility"):
        assert np.array_equal(two.column(column), one.column(column)), column
    assert np.allclose(two.q[two.assembled], one.q[one.assembled], atol=1e-9)
    assert [p.values for p in two.singular] == [p.values for p in one.singular]
    assert two.residual[two.assembled].max() <= two.tolerance.closure


def test_only_the_angles_of_r_and_c_joints_wrap():
    from mobility.sweeps.walks import axis_walk

    z, x = (0.0, 0.0, 1.0), (1.0, 0.0, 0.0)
    m = mobility.Mechanism("serial", "g", "e", (
        mobility.Joint("R1", "R", ("g", "a"), axis=z, point=(0.0, 0.0, 0.0)),
        mobility.Joint("P1", "P", ("a", "b"), axis=x),
        mobility.Joint("H1", "H", ("b", "c"), axis=z, point=(1.0, 0.0, 0.0), pitch=2.0),
        mobility.Joint("C1", "C", ("c", "e"), axis=x, point=(0.0, 1.0, 0.0)),
    ))
    plan = plan_grid(m, ["R1=0:360:3", "P1=0:360:3", "H1=0:360:3", "C1=0:360:3", "rz=-180:180:3"])
    assert [a.period for a in plan.axes] == [360.0, 0.0, 0.0, 360.0, 0.0]
    assert [axis_walk(a).closed for a in plan.axes] == [True, False, False, True, False]
    screw = sweep(m, ["H1=0:360:3"], actuated=[])  # a turn of the screw moves its nut by the pitch times 2 pi
    moved = np.subtract(screw.mechanism_at(2).joint("C1").point, screw.mechanism_at(0).joint("C1").point)
    assert np.allclose(moved, [0.0, 0.0, 2.0 * 2.0 * math.pi], atol=1e-9)
    spin = sweep(m, ["C1=0:360:3"], actuated=[])  # a turn of a C joint is the same joint state: one pose
    assert spin.assembled.all() and np.array_equal(spin.q[2], spin.q[0])  # the driven angle too: solved once, as 0


# --- scale-out, progress -----------------------------------------------------------------------------


def test_chunks_and_threads_give_the_same_answers():
    m = load("3prs")
    vary = ["P1=-20:20:5", "P2=-20:20:5", "P3=-20:20:4"]
    one = sweep(m, vary, workers=1, chunk_size=10_000)
    many = sweep(m, vary, workers=2, chunk_size=7)
    for name in ("dof", "pattern", "mobility", "assembled", "verdict"):
        assert np.array_equal(one.column(name), many.column(name))
    assert np.allclose(one.q, many.q, atol=1e-12) and np.allclose(one.conditioning, many.conditioning, rtol=1e-9)


def test_dask_cluster_runs_the_chunks():
    from dask import distributed

    m = load("3prs")
    vary = ["P1=-20:20:5", "P2=-20:20:6"]
    with distributed.LocalCluster(n_workers=1, threads_per_worker=2, processes=False, dashboard_address=None) as cluster, distributed.Client(cluster) as client:
        on_dask = sweep(m, vary, scheduler=client, chunk_size=7)
        by_address = sweep(load("parallelogram"), ["O1=0:360:73"], scheduler=cluster.scheduler_address, chunk_size=20)
    local = sweep(m, vary)
    for name in ("assembled", "dof", "pattern", "mobility", "verdict"):
        assert np.array_equal(on_dask.column(name), local.column(name))
    assert np.allclose(on_dask.q, local.q, atol=1e-12) and np.allclose(on_dask.conditioning, local.conditioning, rtol=1e-9)
    assert [p.values for p in by_address.singular] == [(120.0,), (300.0,)]


def _most_chunks_out_at_once(runner_, count: int) -> tuple[list[int], int]:
    """Run ``count`` trivial chunks through a sweep runner; the order of the answers and the most chunks built but not yet answered."""
    drawn, answered, most = [0], [0], [0]

    def chunks():
        for i in range(count):
            drawn[0] += 1
            most[0] = max(most[0], drawn[0] - answered[0])
            yield (i,)

    order = []
    for i, value in runner_.run("test", _square, chunks(), [1] * count):
        answered[0] += 1
        assert value == i * i
        order.append(i)
    return order, most[0]


def _square(context, i):
    return i * i


def test_a_sweep_hands_out_a_few_chunks_at_a_time_so_its_memory_stays_bounded():
    from dask import distributed

    from mobility.sweeps import runner

    context = runner._Context(load("parallelogram"), plan_grid(load("parallelogram"), ["O1=0:90:3"]), mobility.DEFAULT_TOLERANCE, None)
    threads = runner._Runner(context, None, 2, None)
    order, most = _most_chunks_out_at_once(threads, 40)
    assert sorted(order) == list(range(40)) and most <= runner.IN_FLIGHT * 2 + 1  # + the one being handed over
    with distributed.LocalCluster(n_workers=1, threads_per_worker=2, processes=False, dashboard_address=None) as cluster, distributed.Client(cluster) as client:
        on_dask = runner._Runner(context, client, None, None)
        order, most = _most_chunks_out_at_once(on_dask, 25)
    assert sorted(order) == list(range(25)) and most <= runner.IN_FLIGHT * on_dask.workers + 1


def test_a_scheduler_that_never_answers_or_has_no_workers_is_refused(monkeypatch):
    import socket

    from dask import distributed

    from mobility.sweeps import runner

    monkeypatch.setattr(runner, "CONNECT_SECONDS", 1.0)
    silent = socket.create_server(("127.0.0.1", 0))  # accepts connections, never speaks
    try:
        address = "tcp://127.0.0.1:%d" % silent.getsockname()[1]
        with time_bound(15), pytest.raises(RequestError, match=r"cannot reach a dask scheduler there \(no answer within 1 s\)"):
            sweep(load("parallelogram"), ["O1=0:90:3"], scheduler=address)
    finally:
        silent.close()
    with distributed.LocalCluster(n_workers=0, processes=False, dashboard_address=None) as cluster:
        with time_bound(15), pytest.raises(RequestError, match="has no workers"):
            sweep(load("parallelogram"), ["O1=0:90:3"], scheduler=cluster.scheduler_address)


@pytest.mark.parametrize("address, why", [("tcp://127.0.0.1:{closed}", "Connection refused"), ("127.0.0.1:{closed}", "Connection refused"),
                                          ("tcp://localhost:99999", "Port out of range 0-65535")])
def test_a_scheduler_address_that_refuses_is_said_at_once(monkeypatch, address, why):
    import socket

    from mobility.sweeps import runner

    probe = socket.create_server(("127.0.0.1", 0))
    closed = probe.getsockname()[1]
    probe.close()  # a port nothing listens on
    monkeypatch.setattr(runner, "CONNECT_SECONDS", 60.0)  # dask's own retries would take this long
    address = address.format(closed=closed)
    with time_bound(10), pytest.raises(RequestError) as info:
        sweep(load("parallelogram"), ["O1=0:90:3"], scheduler=address)
    assert str(info.value) == f"--scheduler {address}: cannot reach a dask scheduler there ({why})"


def test_a_server_that_is_not_a_scheduler_is_one_line_without_distributed_s_traceback():
    import socket
    import struct
    import subprocess
    import sys
    import threading
    import time

    server = socket.create_server(("127.0.0.1", 0))

    def answer(connection: socket.socket) -> None:  # a message of 1,000 empty frames, which distributed cannot decode (it logs a traceback)
        with connection:
            connection.sendall(struct.pack("Q", 1000) + bytes(8000))
            time.sleep(5)

    def serve() -> None:  # every connection (the sweep first checks that the port accepts one)
        while True:
            try:
                connection, _ = server.accept()
            except OSError:  # closed at the end of the test
                return
            threading.Thread(target=answer, args=(connection,), daemon=True).start()

    threading.Thread(target=serve, daemon=True).start()
    address = "tcp://127.0.0.1:%d" % server.getsockname()[1]
    try:  # a process of its own: distributed's log handlers write to the real stderr
        run = subprocess.run(
            [sys.executable, "-m", "mobility", "sweep", str(MECHANISMS / "parallelogram.yaml"), "--vary", "O1=0:90:3", "--scheduler", address],
            capture_output=True, text=True, timeout=60,
        )
    finally:
        server.close()
    assert run.returncode == 2 and run.stderr.count("\n") == 1, run.stderr
    assert "cannot reach a dask scheduler there" in run.stderr and "Traceback" not in run.stderr


def test_progress_reports_both_stages_to_the_end():
    seen: list[tuple[str, int, int]] = []
    sweep(load("parallelogram"), ["O1=0:90:10"], progress=lambda stage, done, total: seen.append((stage, done, total)))
    stages = [s for s, _, _ in seen]
    assert stages[0] == "closing loops" and stages[-1] == "analysing"
    for stage in ("closing loops", "analysing"):
        last = [x for x in seen if x[0] == stage][-1]
        assert last[1] == last[2] == 10


def test_an_interrupt_stops_the_threads_of_a_sweep_before_it_propagates():
    """Ctrl-C in a threaded sweep shuts its pool down at once, even while the traceback is kept alive.

    A reference cycle holding the traceback (as the command line's handler can) kept the chunk generators
    open: the pool's threads went on with the chunks in flight and the process waited for them at exit
    (``mobility sweep`` of 4 million poses did not end within a minute of Ctrl-C once in CI).
    """
    import threading

    def interrupt(stage: str, done: int, total: int) -> None:
        if done:
            raise KeyboardInterrupt

    before = set(threading.enumerate())
    with pytest.raises(KeyboardInterrupt) as kept:  # ``kept`` holds the traceback, and with it every frame of the sweep
        sweep(load("3prs"), ["P1=-30:30:12", "P2=-30:30:12", "P3=-30:30:12"], workers=2, chunk_size=64, progress=interrupt)
    left = [t.name for t in set(threading.enumerate()) - before if t.is_alive()]
    assert kept.value is not None and left == []


# --- bad requests --------------------------------------------------------------------------------------


@pytest.mark.parametrize(
    "vary, message",
    [
        (["Q9=0:1:2"], "'Q9' is not a joint"),
        (["S1=0:10:3"], "S1 is an S joint"),
        (["P1=0:10:0"], "COUNT must be at least 1"),
        (["P1=0:10"], "expected NAME=START:STOP:COUNT"),
        (["P1=a:10:3"], "START must be a number"),
        (["P1=0:inf:3"], "STOP must be a finite number"),
        (["P1=0:1:2.5"], "COUNT must be an integer"),
        (["P1=0:1:2", "P1=0:1:3"], "P1 is varied twice"),
        ([], "at least one coordinate"),
        (["P1=-1e308:1e308:3"], "do not fit in a float"),  # the step itself overflows
        (["R1=-1e308:1e308:3"], "do not fit in a float"),
        (["z=1e6:2e6:3"], r"2e\+06 is beyond what a sweep reaches from the file's pose, 1,000 times the mechanism's size"),
        (["P1=0:3e5:3"], "beyond what a sweep reaches"),
        (["rx=-150:150:3", "ry=-150:150:3"], "rotation vector reaches 212.132 deg, more than half a turn"),
    ],
)
def test_bad_requests_are_one_line_errors(vary, message):
    with pytest.raises(RequestError, match=message) as info:
        sweep(load("3prs"), vary)
    assert "\n" not in str(info.value)


@pytest.mark.parametrize(
    "arguments, error, message",
    [
        (dict(vary=None), RequestError, "vary: expected NAME=START:STOP:COUNT"),
        (dict(vary=1.5), RequestError, "got float"),
        (dict(vary=[("O1", 10**400, 1, 2)]), RequestError, "START must be a finite number, got an integer of 401 digits"),
        (dict(tol=1e-8), RequestError, "tol must be a Tolerance"),
        (dict(max_poses=math.nan), RequestError, "max_poses must be a positive integer, got nan"),
        (dict(max_poses="10"), RequestError, "max_poses must be a positive integer"),
        (dict(scheduler=object()), RequestError, "scheduler must be a dask distributed.Client"),
        (dict(progress="x"), RequestError, "progress must be True, False or a callable"),
        (dict(progress=lambda stage: None), RequestError, "progress must accept three arguments"),
        (dict(actuated="O1"), MechanismError, r"got the string 'O1' \(write \['O1'\]\)"),
        (dict(actuated=5), MechanismError, "expected a sequence of joint names, got int"),
    ],
)
def test_wrong_arguments_from_python_are_mobility_errors(arguments, error, message):
    arguments = {"vary": ["O1=0:90:3"]} | arguments
    with pytest.raises(error, match=message):
        sweep(load("parallelogram"), **arguments)


def test_a_joint_whose_name_holds_an_equals_sign_can_be_swept():
    m = mobility.loads("name: eq\nground: g\nend_effector: l\njoints:\n  - {name: 'A=1', type: R, links: [g, l], axis: [0, 0, 1], point: [0, 0, 0]}\n")
    r = sweep(m, ["A=1=0:90:3"])
    assert [a.name for a in r.axes] == ["A=1"] and r.values[:, 0].tolist() == [0.0, 45.0, 90.0]


def test_a_grid_above_the_cap_is_refused_before_any_work():
    with pytest.raises(RequestError, match="more than --max-poses 1,000"):
        plan_grid(load("3prs"), ["P1=0:1:11", "P2=0:1:11", "P3=0:1:11"], max_poses=1000)
    assert plan_grid(load("3prs"), ["P1=0:1:11", "P2=0:1:11", "P3=0:1:11"], max_poses=1331).size == 1331


def test_a_sweep_reaches_its_limits_and_every_pose_up_to_them_closes():
    from mobility.core.tolerance import SWEEP_REACH

    m = load("3prs")
    size = plan_grid(m, ["z=0:1:2"]).length
    far = sweep(m, [f"z={0.5 * SWEEP_REACH * size}:{SWEEP_REACH * size}:3"])  # starting half way: long steps, far from the origin
    assert far.assembled.all() and far.residual.max() <= far.tolerance.closure and far.counts() == {(3, "1T2R", 3): 3}
    with pytest.raises(RequestError, match="beyond what a sweep reaches"):
        plan_grid(m, [f"z=0:{1.01 * SWEEP_REACH * size}:3"])
    scara = load("scara")
    turned = sweep(scara, ["rz=-180:180:9"])  # the principal rotation vector: up to half a turn each way
    assert turned.assembled.all() and turned.counts() == {(4, "3T1R", 4): 9}


def test_an_unknown_input_is_a_mechanism_error():
    with pytest.raises(MechanismError, match="unknown joint 'Z'"):
        sweep(load("3prs"), ["P1=0:1:2"], actuated=["Z"])


# --- properties ---------------------------------------------------------------------------------------


@settings(max_examples=6, deadline=None)
@given(scale=st.sampled_from([0.001, 25.4, 1000.0]), count=st.integers(2, 6), reach=st.floats(5.0, 30.0))
def test_a_sweep_does_not_depend_on_the_length_unit(scale, count, reach):
    m = load("3rps")  # three legs driven: the pose is determined
    scaled = m.replace(joints=tuple(j.transformed(_scaling(scale)) for j in m.world_joints))
    a = sweep(m, [f"P1={-reach}:{reach}:{count}", "P2=-5:5:2", "P3=3:3:1"])
    b = sweep(scaled, [f"P1={-reach * scale}:{reach * scale}:{count}", f"P2={-5 * scale}:{5 * scale}:2", f"P3={3 * scale}:{3 * scale}:1"])
    for name in ("assembled", "dof", "pattern", "mobility", "verdict"):
        assert np.array_equal(a.column(name), b.column(name))
    assert np.allclose(a.q, b.q, atol=1e-9) and np.allclose(a.conditioning, b.conditioning, rtol=1e-7)


def _scaling(k: float):
    from mobility.core.transforms import Transform

    return Transform(np.eye(3) * k, np.zeros(3))


def test_every_way_of_writing_the_request_gives_the_same_grid():
    m = load("parallelogram")
    text = sweep(m, "O1=0:360:13")
    for vary in (["O1=0:360:13"], [("O1", 0, 360, 13)], {"O1": (0, 360, 13)}):
        other = sweep(m, vary)
        assert other.axes == text.axes and np.array_equal(other.mobility, text.mobility)
    assert text.axes[0].values.tolist() == [30.0 * k for k in range(13)] and text.axes[0].label == "O1 [deg]"
    single = sweep(m, "O1=45:45:1")
    assert single.size == 1 and single.values.tolist() == [[45.0]]


def test_a_sweep_at_any_scale_is_the_sweep_scaled_without_a_warning():
    import warnings

    m = load("3prs")
    plain = sweep(m, ["P1=0:20:3"])
    for k in (1e200, 1e-250):
        big = m.replace(joints=tuple(j.transformed(_scaling(k)) for j in m.world_joints), frames=())
        with warnings.catch_warnings():
            warnings.simplefilter("error")  # an overflow in the solver would be a warning
            scaled = sweep(big, [f"P1=0:{20 * k!r}:3"])
            # a target far beyond the mechanism (within reach of the solver): P1 slid 470 sizes while P2 and P3
            # stay where the file has them, so no leg reaches; not assembled, quietly.  (With P2 and P3 free the
            # whole head could follow P1 up: that pose exists, and whether one 470-size step's Newton closed it
            # to 1e-12 was round-off's choice, different from one BLAS kernel to another.)
            far = sweep(big, [f"P1=0:{1e5 * k!r}:2", "P2=0:0:1", "P3=0:0:1"])
        assert np.array_equal(scaled.assembled, plain.assembled) and np.array_equal(scaled.pattern, plain.pattern)
        assert np.allclose(scaled.conditioning, plain.conditioning, rtol=1e-7)
        assert scaled.values[:, 0] / k == pytest.approx(plain.values[:, 0], rel=1e-12)
        assert far.assembled.tolist() == [True, False]
        with pytest.raises(RequestError, match="beyond what a sweep reaches"):
            sweep(big, [f"P1=0:{1e6 * 20 * k!r}:2"])
        if k < 1:  # 1e300 over a size of about 1e-248: not a float
            with pytest.raises(RequestError, match="x=0:1e.300:3: its values do not fit in a float"):
                sweep(big, ["x=0:1e300:3"])
        assert f"P1 from 0 to {20 * k:g}" in sweep_summary(scaled)  # shown against the range, not rounded to 0
        assert sweep_csv(scaled).splitlines()[2].startswith(f"{10 * k:g},")


def test_a_deep_tree_is_evaluated_for_every_pose_without_recursion():
    import sys

    from mobility.core.screw_systems import evaluate, per_pose

    z = (0.0, 0.0, 1.0)
    n = 1500  # a ladder of rigid triangles: series inside parallel 1,500 deep
    joints = [mobility.Joint(f"A{i}", "R", ("g", f"l{i}"), axis=z, point=(float(i), 0.0, 0.0)) for i in range(n + 1)]
    joints += [mobility.Joint(f"B{i}", "R", (f"l{i}", f"l{i + 1}"), axis=z, point=(i + 0.5, 1.0 + 0.25 * math.sin(i), 0.0)) for i in range(n)]
    m = mobility.Mechanism("ladder", "g", f"l{n}", tuple(joints))
    limit = sys.getrecursionlimit()
    sys.setrecursionlimit(1000)  # Python's default: a library run earlier in this process (mypy) may have raised it
    try:
        assert n > sys.getrecursionlimit()
        screws = joint_screws(m)
        twists = np.broadcast_to(screws.twists, (2, *screws.twists.shape))
        value = evaluate(decompose(m).root, np.ascontiguousarray(twists), screws.offsets)
        single = evaluate(decompose(m).root, screws.twists[None], screws.offsets)
    finally:
        sys.setrecursionlimit(limit)
    assert per_pose(value.dim, 2).tolist() == per_pose(single.dim, 1).tolist() * 2 and per_pose(value.mobility, 2).tolist() == per_pose(single.mobility, 1).tolist() * 2 == [0, 0]


def test_a_type_two_singularity_between_grid_points_is_a_margin_dip():
    # The legs lie in the platform's plane at z = 0: actuation and constraint forces are coplanar, three
    # uncontrolled freedoms; on both sides the inputs are valid, so no answer changes across it.
    m = mobility.loads(flat_3rps())
    assert mobility.check_actuation(m, ["P1", "P2", "P3"]).verdict == "actuation-singular"
    off = sweep(m, ["z=-20.25:19.75:81", "rx=0:0:1", "ry=0:0:1"])  # misses z = 0 by a quarter step
    assert off.singular == () and len(off.changes) == 0 and off.verdict_counts() == {"valid": 81}
    assert off.dips and {(d.column, abs(d.values[0])) for d in off.dips} == {("actuation_margin", 0.25)}
    assert float(np.min(off.conditioning)) > 0.4  # kappa does not see the three inputs vanish together
    for d in off.dips:  # the second route: the pose rebuilt and checked on its own
        alone = mobility.check_actuation(off.mechanism_at(d.index), ["P1", "P2", "P3"])
        assert alone.verdict == "valid" and alone.margin.smallest_kept == pytest.approx(d.margin, rel=1e-6)
        assert d.margin < 0.5 * max(d.neighbours)
    on = sweep(m, ["z=-20:20:81", "rx=0:0:1", "ry=0:0:1"])  # through z = 0: the singular pose itself, no dip beside it
    assert [p.values[0] for p in on.singular] == [0.0] and on.dips == ()
    assert "margin dips (" in sweep_summary(off) and "actuation margin (distance to an actuation singularity): smallest" in sweep_summary(off)
    assert json.loads(sweep_json(off))["margin_dips"][0]["column"] == "actuation_margin"


def test_poses_a_hair_from_an_actuation_singularity_are_counted_near_it_as_the_one_pose_check_warns():
    m = mobility.loads(flat_3rps())  # the legs in the platform's plane at z = 0: actuation-singular there
    r = sweep(m, ["z=-0.0025:0.0025:3", "rx=0:0:1", "ry=0:0:1"])  # an actuation margin of 7.7e-6 on each side
    assert r.verdict.tolist() == ["valid", "actuation-singular", "valid"]
    warned = [any("near an actuation singularity" in w for w in mobility.check_actuation(r.mechanism_at(i), ["P1", "P2", "P3"]).warnings) for i in (0, 2)]
    assert warned == [True, True]  # the second route: each pose checked on its own warns
    assert "; near an actuation singularity: 2" in sweep_summary(r)  # (was not counted: "near-singular poses: 0" only)
    far = sweep(m, ["z=10:20:3", "rx=0:0:1", "ry=0:0:1"])
    assert "; near an actuation singularity: 0" in sweep_summary(far)


def test_a_dead_centre_between_grid_points_and_at_the_grid_end_are_margin_dips():
    m = mobility.load(MECHANISMS / "slider_crank.yaml")  # dead centres at -60 and 120 degrees from the file's pose
    r = sweep(m, ["O=-59.75:120.25:181"])
    assert r.singular == () and len(r.changes) == 0
    found = {(round(d.values[0], 2), d.column, len(d.neighbours)) for d in r.dips}
    assert found == {(-59.75, "smallest_kept", 1), (120.25, "smallest_kept", 1)}  # each end a quarter degree past a dead centre
    assert r.dips[0].margin < 0.5 * r.dips[0].neighbours[0]
    through = sweep(m, ["O=-60:120:181"])
    assert [p.values[0] for p in through.singular] == [-60.0, 120.0] and through.dips == ()


def test_a_sweep_leaves_a_fold_of_its_drive_on_the_side_where_poses_exist():
    # The slider-crank at its outer dead centre, driven by its slider: the slider is at its farthest, so
    # only one side of the grid can be assembled, and there the crank turns by sqrt(step), along the motion
    # the drive leaves free at the fold (Newton's minimum-norm step alone never takes it).
    text = (MECHANISMS / "slider_crank.yaml").read_text()
    assert "phi: 60" in text
    m = mobility.loads(text.replace("phi: 60", "phi: 0"))
    r = sweep(m, ["G=-2:2:21"])
    g = r.values[:, 0]
    assert r.assembled.tolist() == (g >= 0).tolist()
    crank = r.q[:, kinematics(m).variables_of("O")][:, 0]
    x = 40.0 + 120.0 - g[r.assembled]  # the second route: the crank angle of that slider position, closed form
    assert np.abs(crank[r.assembled]) == pytest.approx(np.arccos((40.0**2 + x**2 - 120.0**2) / (2 * 40.0 * x)), abs=1e-9)
    assert len(set(np.sign(crank[r.assembled][1:]).tolist())) == 1  # one branch, not a zigzag between the two
    assert r.dof[r.assembled].tolist() == [0] + [1] * 10  # at the dead centre the slider is stopped


def test_joints_that_meet_on_a_link_still_meet_in_every_rebuilt_pose():
    # The Schatz linkage's first two axes meet at the origin.  Carried by different links, the moved
    # points came out 3.6e-15 apart (round-off of the size 68), which the analysis refused as a link
    # narrower than it can resolve; a rigid link keeps them together.
    m = mobility.load(MECHANISMS / "schatz.yaml")
    assert m.joints[0].point == m.joints[1].point
    r = sweep(m, ["J4=-6:6:13"])
    assert r.assembled.all()
    for i in range(r.size):  # the second route: each pose rebuilt and analysed alone
        pose = r.mechanism_at(i)
        assert pose.joints[0].point == pose.joints[1].point
        alone = mobility.analyze(pose)
        assert (alone.dof, alone.pattern, alone.mobility) == (int(r.dof[i]), str(r.pattern[i]), int(r.mobility[i])) == (1, "1R", 1)


def test_a_reachable_pose_is_assembled_whatever_the_grid_step():
    # The tilted 3-PRS driven by R1: the other joints move about 25 times faster than R1 near the file's
    # pose, so a line's first step must move them far more than the drive itself.  A half-degree grid
    # reaches R1 from -19.45 deg up along the minimum-norm path (found independently by a 0.05-degree
    # least-squares walk); it used to assemble 1 of 241 poses, since smaller steps shrank the allowed move
    # with them.  R1 alone leaves the 3-PRS two freedoms, so the pose depends on the path: towards -19.45
    # the sliders run off to hundreds of lengths, and where a grid's path gives up there depends on its
    # step (a 0.1-degree grid stops a few tenths of a degree short); above -18.5 every grid reaches all.
    m = load("3prs_tilted")
    coarse, fine = sweep(m, ["R1=-60:60:241"]), sweep(m, ["R1=-60:60:1201"])
    assert coarse.assembled.tolist() == (coarse.values[:, 0] >= -19.45).tolist()
    lowest = fine.values[fine.assembled, 0].min()
    assert -19.5 < lowest < -18.5
    assert fine.assembled.tolist() == (fine.values[:, 0] >= lowest).tolist()
    for i in random_rows(coarse, 3):
        assert_pose_matches_one_pose_routes(coarse, i)
    # a pose coordinate driven in one long step: the wrist's platform raised by 1.769 in one step, as in 40
    one, many = sweep(load("3upu_wrist"), ["z=0:1.769:2"]), sweep(load("3upu_wrist"), ["z=0:1.769:41"])
    assert one.assembled.all() and many.assembled.all()
    assert_pose_matches_one_pose_routes(one, 1)


def test_a_rotation_a_translational_platform_cannot_make_is_not_assembled_on_another_branch():
    # The Tsai 3-UPU and the Delta translate: no motion from the file's pose turns the platform, so a
    # sweep of a rotation assembles the file's pose only.  Starts far along the translations (tried at a
    # fold of the drive) used to close poses of other assemblies, with legs 39 times the mechanism's size
    # and tilts that jumped from one grid point to the next; now a pose found off a fold is kept only if
    # walking back from it reaches the fold's pose.
    for name, vary in [("tsai_3upu", "rx=-10:10:25"), ("delta", "ry=-10:10:7"), ("delta", "ry=-10:10:25")]:
        r = sweep(load(name), [vary])
        assert r.assembled.tolist() == (r.values[:, 0] == 0).tolist(), (name, vary)
        assert mobility.analyze(r.mechanism_at(int(np.flatnonzero(r.assembled)[0]))).pattern == "3T"
    # where the rotation is a freedom, holding x still as well reaches every pose (it used to reach 1 of 7)
    m = load("pkm_sp1rc_4ups")
    alone, with_x = sweep(m, ["ry=-10:10:7"]), sweep(m, ["x=0:0:1", "ry=-10:10:7"])
    assert alone.assembled.all() and with_x.assembled.all()
    for i in (0, 6):
        assert_pose_matches_one_pose_routes(with_x, i)


def test_a_branch_with_a_second_order_freedom_is_never_reported_clean_with_another_pattern():
    # 4puu_singular: along its translations the platform's rotation stays an infinitesimal freedom (the
    # finite analysis: instantaneous-only, first-order 3T1R on the whole branch).  The closure pins that
    # rotation only to about 1e-7, so a row may show what round-off leaves; it must then say so.
    m = load("4puu_singular")
    finite = mobility.finite_mobility(m)
    assert (finite.verdict, finite.branches[0].analysis.pattern) == ("instantaneous-only", "3T1R")
    for vary in (["P1=-1:1:9"], ["x=-1:1:9"]):
        r = sweep(m, vary)
        rows = np.flatnonzero(r.assembled)
        assert rows.size == 9
        clean = rows[~r.near_singular[rows]]
        assert all(r.pattern[i] == "3T1R" and r.dof[i] == 4 for i in clean), vary
        assert (r.smallest_kept[rows[r.near_singular[rows]]] < 1e-5).all()
    # the exact branch pose: every slider moved by the same amount, a pure translation along x
    k = kinematics(m)
    q = np.zeros(k.variable_count)
    for name in ("P1", "P2", "P3", "P4"):
        q[k.variables_of(name)] = 0.5 / k.normalisation.length
    assert np.abs(k.residual(q)).max() == 0.0
    assert mobility.analyze(k.mechanism_at(q)).pattern == "3T1R"


# --- continuation: coarse steps, full turns, residuals, chunks --------------------------------

_AXIS_3RRR = [-0.3163144964919387, -0.49309860600178157, 0.8104313074333636]
_JOINTS_3RRR = [
    ("A1", "ground, p1", [3.0, -1.0, 2.0]),
    ("B1", "p1, d1", [1.5960394807787979, 2.052096716422004, 3.3090456424717027]),
    ("C1", "d1, platform", [3.0055103960508163, 3.028746401984467, 4.453400102721235]),
    ("A2", "ground, p2", [8.037760694579221, 5.36571059271199, 7.839408859977784]),
    ("B2", "p2, d2", [4.216777121170155, 6.168015505029132, 6.836218270204397]),
    ("C2", "d2, platform", [3.8522950244241905, 4.420485493718839, 5.630692799415202]),
    ("A3", "ground, p3", [-0.9118200744091798, 6.926734224034944, 5.2961414179252815]),
    ("B3", "p3, d3", [0.6947529518053543, 4.935015211718313, 4.711352150396937]),
    ("C3", "d3, platform", [2.303530136440215, 4.5547947601954695, 5.107922923957087]),
]


def planar_3rrr_near_a_fold() -> mobility.Mechanism:
    """A planar 3-RRR in a tilted plane whose file pose lies 1.18 degrees of A1 below a fold (A2, A3 held)."""
    joints = "".join(f"  - {{name: {n}, type: R, links: [{links}], axis: {_AXIS_3RRR}, point: {p}}}\n" for n, links, p in _JOINTS_3RRR)
    return mobility.loads(f"name: planar 3-RRR near a fold\nground: ground\nend_effector: platform\njoints:\n{joints}")


def assert_same_poses_as_a_finer_grid(coarse: SweepResult, fine: SweepResult) -> None:
    """Every value of ``coarse`` is a value of ``fine`` (its first axis ``k`` times finer): the same poses assembled, at the same joint variables."""
    k = (fine.shape[0] - 1) // (coarse.shape[0] - 1)
    assert np.array_equal(coarse.values[:, 0], fine.values[::k, 0])
    assert coarse.assembled.tolist() == fine.assembled[::k].tolist()
    both = coarse.assembled
    assert np.abs(coarse.q[both] - fine.q[::k][both]).max() < 1e-9


def test_a_coarse_step_near_a_fold_is_walked_in_sub_steps():
    # The file's pose lies 1.18 deg of A1 below a fold, where the other joints move about 16 times faster
    # than A1: a 2-degree step from it must move them 0.57, farther than a first step (predicted from one
    # point) may move.  Such a step is walked in halved sub-steps from its assembled neighbour: every pose
    # below the fold is assembled on any grid, at the joint variables a 0.1-degree grid finds (it used to
    # assemble the file's pose only), and no pose above the fold (none is reachable from the file's pose).
    m = planar_3rrr_near_a_fold()
    assert sweep(m, ["A1=-2:0:2", "A2=0:0:1", "A3=0:0:1"]).assembled.all()
    fine = sweep(m, ["A1=-30:30:601", "A2=0:0:1", "A3=0:0:1"])
    assert fine.assembled.tolist() == (fine.values[:, 0] < 1.15).tolist()  # the fold lies at about +1.18
    for count in (31, 61):
        coarse = sweep(m, [f"A1=-30:30:{count}", "A2=0:0:1", "A3=0:0:1"])
        assert_same_poses_as_a_finer_grid(coarse, fine)
    assert_pose_matches_one_pose_routes(coarse, 0)
    # the 3-UPU wrist passes from its spherical 3R mode to a 1T2R mode near P1 = -21.7 and +15: a walk
    # from the file's pose reaches every pose, and a 1-length grid (47 of 65 assembled before) finds the
    # poses of a 0.25-length grid
    wrist = load("3upu_wrist")
    fine = sweep(wrist, ["P1=-32:32:257", "P2=0:0:1", "P3=0:0:1"])
    coarse = sweep(wrist, ["P1=-32:32:65", "P2=0:0:1", "P3=0:0:1"])
    assert fine.assembled.all()
    assert_same_poses_as_a_finer_grid(coarse, fine)
    assert {str(p) for p in coarse.pattern} == {"3R", "1T2R"}


def test_a_sub_stepped_walk_does_not_cross_a_fold_onto_another_branch():
    # A1 above the fold is reachable only on the other assembly branch (by a walk that goes round the
    # fold, which a monotonic drive cannot do): from the last pose below the fold, however small the
    # sub-steps, nothing above is assembled, on coarse and fine grids alike
    m = planar_3rrr_near_a_fold()
    for vary in ("A1=0:30:16", "A1=0:2:21", "A1=-1:1.5:2"):
        r = sweep(m, [vary, "A2=0:0:1", "A3=0:0:1"])
        assert r.assembled.tolist() == (r.values[:, 0] < 1.15).tolist(), vary


def test_a_full_turn_is_walked_in_one_direction_so_neighbours_are_joined_by_motion():
    # The file's four-bar sits at a change point, which it leaves on one branch turning up and on the
    # other turning down: walked up half way and down the other half, the two halves met at 180 deg on
    # different branches (joint D jumped by 2.86 rad between 180 and 185 deg, a regular pose).  Walked
    # up all the way round, every pair of neighbouring rows is joined by the motion, the last (355 deg)
    # included with the first (0 deg, the file's pose again after a full turn).
    m = load("four_bar_change_point")
    for vary in ("A=0:360:73", "A=-180:180:73"):
        r = sweep(m, [vary])
        assert r.assembled.all()
        step = np.diff(np.concatenate([r.q, r.q[:1]]), axis=0)
        wrapped = np.abs((step + np.pi) % (2 * np.pi) - np.pi)  # every joint is an R joint
        assert wrapped.max() < 0.2, vary  # a 5-degree step of the crank moves no joint farther
    # both ranges walk the same stops from 0 deg up: the same joint states
    up, centred = sweep(m, ["A=0:360:73"]), sweep(m, ["A=-180:180:73"])
    assert np.abs(np.angle(np.exp(1j * (up.q[36:72] - centred.q[:36])))).max() < 1e-9


def true_residuals(r: SweepResult) -> np.ndarray:
    """The largest loop residual component of every row's stored joint variables (and of its pose coordinates), pose by pose."""
    bk = kinematics(r.mechanism)  # the reference point of pose coordinates is the sweep's
    drive = Drive.of(r.axes, bk.variable_count)
    index = np.unravel_index(np.arange(r.size), r.shape)
    targets = np.stack([a.internal[i] for a, i in zip(r.axes, index)], axis=-1)
    return np.array([residuals(bk, drive, r.q[i : i + 1], targets[i : i + 1])[0] for i in range(r.size)])


def test_the_residual_column_is_the_residual_of_the_stored_joint_variables():
    # Every row of the line through the file's pose used to show a residual of exactly 0 (the start of a
    # line was never measured), so the summary read "largest loop-closure residual 0.0e+00"
    r = sweep(load("3prs"), ["P1=-30:30:5", "P2=0:0:1"])
    k = kinematics(r.mechanism)
    loop = np.array([np.abs(k.residual(q)).max() for q in r.q])
    assert r.assembled.all() and r.residual.max() > 0.0
    assert np.array_equal(r.residual, true_residuals(r))
    assert np.abs(r.residual - loop).max() < 1e-15
    # a pose polished for its analysis (near the parallelogram's change point) carries the residual of
    # its polished joint variables, not the one measured before polishing
    near = sweep(load("parallelogram"), ["O1=119.99:120.01:5"])
    assert near.near_singular.sum() == 2 and np.array_equal(near.residual, true_residuals(near))


def test_a_pose_not_assembled_carries_the_residual_of_its_joint_variables():
    # It used to carry the best residual of any attempt, such as a pose of another assembly found off a
    # fold and refused (1e-15), with joint variables whose residual is 2e-2
    r = sweep(load("tsai_3upu"), ["x=-20:20:9", "rz=-5:5:3"])
    missing = np.flatnonzero(~r.assembled)
    assert missing.size == 18 and (r.residual[missing] > r.tolerance.closure).all()
    assert np.array_equal(r.residual, true_residuals(r))


def test_a_sweep_does_not_depend_on_its_chunk_size():
    # The batched kinematics gives every pose the same bits whatever the batch around it, so a sweep cut
    # into chunks of one line gives the same table, the joint variables of poses not assembled included
    # (a Newton solve that cannot close a pose amplifies its round-off: they used to differ by 2e-4)
    m = load("tsai_3upu")
    whole, cut = sweep(m, ["x=-20:20:9", "rz=-5:5:3"]), sweep(m, ["x=-20:20:9", "rz=-5:5:3"], chunk_size=1)
    for column in ("q", "residual", "assembled"):
        assert np.array_equal(getattr(whole, column), getattr(cut, column)), column
    bk = kinematics(m)
    q = np.random.default_rng(RNG_SEED).normal(size=(7, bk.variable_count))
    together = bk.evaluate(q, np.arange(6))
    for i in range(7):
        alone = bk.evaluate(q[i : i + 1], np.arange(6))
        assert np.array_equal(alone.values[:, 0], together.values[:, i])
        assert np.array_equal(alone.jacobian()[:, :, 0], together.jacobian()[:, :, i])


# -- seams: a full turn that comes back on another pose ---------------------------------------------


def _point(result: SweepResult, index: int, joint: str) -> np.ndarray:
    """A joint's point at a grid point, from the pose rebuilt as a mechanism (the independent route)."""
    return np.array(next(j.point for j in result.mechanism_at(index).world_joints if j.name == joint))


def test_a_full_turn_whose_free_joint_drifts_is_reported_as_a_seam():
    # the 5R driven by one crank of its two: A2 follows the solver, and after a turn of A1 it is elsewhere;
    # the table held two neighbouring poses (359 and 0 degrees) that no small motion joins, and said nothing
    r = sweep(mobility.load(MECHANISMS / "planar_5r.yaml"), ["A1=0:360:361"])
    assert r.seams.tolist() == [[359, 0]]
    jumps = [np.linalg.norm(_point(r, i + 1, "P") - _point(r, i, "P")) for i in (357, 358)]
    assert max(jumps) < 20.0 and np.linalg.norm(_point(r, 0, "P") - _point(r, 359, "P")) > 100.0  # mm: a step, then a jump
    assert "seams: at 1 pair of neighbouring poses a full turn comes back on another pose" in sweep_summary(r)
    assert "    A1=359 deg -> A1=0 deg" in sweep_summary(r)
    assert json.loads(sweep_json(r))["seams"] == [{"from": 359, "to": 0}]


def test_a_full_turn_that_reaches_another_assembly_is_a_seam_at_that_line_only():
    # both cranks driven, the second round a full turn: at A1 = 300 the distal links flip to their other assembly
    r = sweep(mobility.load(MECHANISMS / "planar_5r.yaml"), ["A1=0:360:73", "A2=0:360:37"])
    (a, b), = r.seams.tolist()
    assert r.values[a].tolist() == [300.0, 350.0] and r.values[b].tolist() == [300.0, 0.0]
    assert abs(_point(r, a, "P")[1] - _point(r, b, "P")[1]) > 300.0  # the distal joint below the base line, then above it
    assert r.changes.size == 0 or not any({int(x), int(y)} == {a, b} for x, y, _ in r.changes)  # the answers alone did not show it


@pytest.mark.parametrize("name, vary", [("four_bar.yaml", ["A=0:360:361"]), ("parallelogram.yaml", ["O1=0:360:361"]),
                                        ("slider_crank.yaml", ["A=-180:180:361"]), ("four_bar.yaml", ["A=0:350:36"]),
                                        ("3rps.yaml", ["R1=0:360:73"]),  # half the turn assembled: the legs meet at the anchor
                                        ("delta.yaml", ["A1=0:360:37", "A2=0:0:1", "A3=0:0:1"])])  # rods spin idly: no joint moves
def test_a_full_turn_that_comes_back_has_no_seam(name, vary):
    r = sweep(mobility.load(MECHANISMS / name), vary)
    assert r.seams.shape == (0, 2) and "seams" not in sweep_summary(r)


def test_arms_driven_at_every_joint_have_the_one_pose_verdict_and_margin_at_every_pose():
    # A planar 4R arm and a spatial 7R arm, every joint driven: a joint whose motion the others produce has no
    # wrench of its own, and what holds the arm is the limb with all its inputs locked (both routes; the batch
    # said "actuation-singular" with every pose's inputs "useless", as the one-pose check did).
    rng = np.random.default_rng(RNG_SEED)
    seven = "\n".join(
        f"  - {{name: J{i + 1}, type: R, links: [{'g' if i == 0 else f'l{i}'}, {'hand' if i == 6 else f'l{i + 1}'}], "
        f"axis: {rng.normal(size=3).round(3).tolist()}, point: {rng.normal(size=3).round(3).tolist()}, actuated: true}}"
        for i in range(7)
    )
    planar = """
  - {name: J1, type: R, links: [g, a], axis: [0, 0, 1], point: [0, 0, 0], actuated: true}
  - {name: J2, type: R, links: [a, b], axis: [0, 0, 1], point: [1, 0, 0], actuated: true}
  - {name: J3, type: R, links: [b, c], axis: [0, 0, 1], point: [2, 0.5, 0], actuated: true}
  - {name: J4, type: R, links: [c, hand], axis: [0, 0, 1], point: [3, 0, 0], actuated: true}"""
    for joints, vary in ((planar, "J2=-30:30:7"), (seven, "J3=-20:20:5")):
        m = mobility.loads(f"name: arm\nground: g\nend_effector: hand\njoints:{joints if joints.startswith(chr(10)) else chr(10) + joints}\n")
        result = sweep(m, vary)
        assert set(result.verdict) == {"redundant"}
        for i in range(result.size):
            assert_pose_matches_one_pose_routes(result, i)
            check = mobility.check_actuation(result.mechanism_at(i), tol=result.tolerance)
            assert result.actuation_margin[i] == pytest.approx(check.margin.smallest_kept, rel=1e-6, abs=1e-12)


@pytest.mark.parametrize("huge, same, reached", [(3e17, 120.0, False), (1e18, 280.0, True), (5e19, 320.0, True), (-1e18, 80.0, False)])
def test_a_huge_angle_is_the_angle_of_its_remainder(huge, same, reached):
    # Whole turns were removed as round(x / 360) * 360, which is not exact beyond 2**53: 3e17 degrees (120 deg,
    # where the four-bar's crank cannot go) was solved as the file's pose and reported assembled.
    assert math.fmod(huge, 360.0) % 360.0 == same  # the remainder, exact in floating point
    m = load("four_bar")  # the crank reaches -160.8 .. +34.0 deg from the file's pose
    far, near = sweep(m, [f"A=0:{huge!r}:2"]), sweep(m, [f"A={same!r}:{same!r}:1"])
    assert bool(far.assembled[1]) == bool(near.assembled[0]) == reached
    if reached:
        assert far.smallest_kept[1] == pytest.approx(near.smallest_kept[0], rel=1e-9)
