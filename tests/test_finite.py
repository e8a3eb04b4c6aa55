"""Instantaneous or full-cycle mobility (mobility.finite).

The cases of the issue, built in code (and from the library files where they
exist), each checked against what is known independently: the literature, a
closed-form branch tangent, the rotation of the platform along a branch, or a
continuation that follows a branch far from the pose.
"""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest
from builders import transformed

import mobility
from mobility.cli import main
from mobility.errors import MechanismFileError
from mobility.core.kinematics import kinematics
from mobility.core.poses import sample_poses
from mobility.errors import RequestError
from mobility.finite import VERDICTS, finite_mobility
from mobility.report.finite import finite_report
from mobility.core.model import Joint, Mechanism
from mobility.core.transforms import Transform, displacement_log, rotation_from_axis_angle

MECHANISMS = Path(__file__).resolve().parent.parent / "mechanisms"


# ---------------------------------------------------------------------------
# mechanisms built in code
# ---------------------------------------------------------------------------


def _r(name, a, b, point, axis=(0, 0, 1)):
    return Joint(name, "R", (a, b), axis=tuple(float(x) for x in axis), point=tuple(float(x) for x in point))


def four_bar(points, name="four-bar"):
    a, b, c, d = points
    return Mechanism(name, "ground", "coupler", (_r("A", "ground", "crank", a), _r("B", "crank", "coupler", b),
                                                _r("C", "coupler", "rocker", c), _r("D", "rocker", "ground", d)))


def flat_four_bar():
    """Crank 1 + coupler 2 + rocker 3 = ground 6: assembled only stretched flat."""
    return four_bar([(0, 0, 0), (1, 0, 0), (3, 0, 0), (6, 0, 0)], "flat four-bar")


def folded_parallelogram():
    """Ground 2, crank 1, coupler 2, rocker 1, folded flat (a change point)."""
    return four_bar([(0, 0, 0), (1, 0, 0), (3, 0, 0), (2, 0, 0)], "folded parallelogram")


def _dh(theta, a, alpha):
    ct, st, ca, sa = np.cos(theta), np.sin(theta), np.cos(alpha), np.sin(alpha)
    return np.array([[ct, -st * ca, st * sa, a * ct], [st, ct * ca, -ct * sa, a * st], [0, sa, ca, 0], [0, 0, 0, 1.0]])


def spatial_4r(a, alpha, b, beta, theta1, theta2, theta3, name):
    """Four R joints along the z axes of a Denavit-Hartenberg chain (links a, b, a; twists alpha, beta, alpha)."""
    frames = [np.eye(4)]
    for th, (length, twist) in zip((theta1, theta2, theta3), ((a, alpha), (b, beta), (a, alpha))):
        frames.append(frames[-1] @ _dh(th, length, twist))
    links = ["ground", "link1", "coupler", "link3", "ground"]
    joints = tuple(_r(f"J{i + 1}", links[i], links[i + 1], f[:3, 3], f[:3, 2]) for i, f in enumerate(frames))
    return Mechanism(name, "ground", "coupler", joints)


def bennett(a=1.0, alpha=np.radians(50), beta=np.radians(75), theta1=0.7):
    """Bennett's linkage from its conditions: b = a sin(beta) / sin(alpha), theta2 from Bennett's relation."""
    b = a * np.sin(beta) / np.sin(alpha)
    theta2 = 2 * np.arctan(np.sin((beta + alpha) / 2) / np.sin((beta - alpha) / 2) / np.tan(theta1 / 2))
    return spatial_4r(a, alpha, b, beta, theta1, theta2, -theta1, "Bennett")


def generic_4r():
    return spatial_4r(1.0, np.radians(50), 1.3, np.radians(75), 0.7, 2.0, -0.7, "generic 4R")


def tsai_3upu(p=(2.0, 0.0, 1.5), rb=2.0, rp=1.0):
    """Tsai's 3-UPU with the platform translated to ``p`` (orientation of the base).

    Each leg's constraint couple is along the leg direction projected on the
    plane normal to the base U's outer axis; with ``rho_i`` the radial offset
    of leg ``i`` the couples are dependent (a constraint singularity) when
    ``rho1 rho2 + rho2 rho3 + rho3 rho1 = 0``: at ``p = (2, 0, h)`` with
    ``rb = 2, rp = 1`` (``rho = 1, -2, -2``).
    """
    p = np.asarray(p, dtype=float)
    joints = []
    for i in range(3):
        ang = 2 * np.pi * i / 3
        r = np.array([np.cos(ang), np.sin(ang), 0.0])
        t = np.array([-np.sin(ang), np.cos(ang), 0.0])
        base, top = rb * r, p + rp * r
        leg = (top - base) / np.linalg.norm(top - base)
        mid = np.cross(t, leg)
        mid /= np.linalg.norm(mid)
        joints += [
            Joint(f"U{i + 1}a", "U", ("base", f"cylinder{i + 1}"), point=tuple(base), axes=(tuple(t), tuple(mid))),
            Joint(f"P{i + 1}", "P", (f"cylinder{i + 1}", f"piston{i + 1}"), axis=tuple(leg)),
            Joint(f"U{i + 1}b", "U", (f"piston{i + 1}", "platform"), point=tuple(top), axes=(tuple(mid), tuple(t))),
        ]
    return Mechanism("3-UPU", "base", "platform", tuple(joints))


def puu4(singular=True, h=1.0):
    """A 4-PUU Schönflies platform: vertical sliders, U joints with vertical outer axes and parallel middle axes.

    Generic: rods point inwards, the middle axes differ, the four constraint
    couples span the horizontal plane: 3T1R.  Singular variant: every rod lies
    in a plane parallel to xz, so every middle axis is along y, the couples are
    all along x, and the platform gains a rotation about y.
    """
    z = np.array([0.0, 0.0, 1.0])
    base = [np.array(v, dtype=float) for v in ([1, 0, 0], [0, 1, 0], [-1, 0, 0], [0, -1, 0])]
    tops = [b + np.array([0.6, 0.0, h]) for b in base] if singular else [0.5 * b + h * z for b in base]
    joints = []
    for i, (b, t) in enumerate(zip(base, tops)):
        u = np.cross(z, t - b)
        u /= np.linalg.norm(u)
        joints += [
            Joint(f"P{i + 1}", "P", ("base", f"slider{i + 1}"), axis=(0, 0, 1)),
            Joint(f"U{i + 1}a", "U", (f"slider{i + 1}", f"rod{i + 1}"), point=tuple(b), axes=((0, 0, 1), tuple(u))),
            Joint(f"U{i + 1}b", "U", (f"rod{i + 1}", "platform"), point=tuple(t), axes=(tuple(u), (0, 0, 1))),
        ]
    return Mechanism("4-PUU singular" if singular else "4-PUU", "base", "platform", tuple(joints))


def straight_truss_on_crank():
    """A two-bar chain stretched straight between two points of a link pivoted on the ground.

    The chain's middle joint has a first-order motion at every pose the
    carrier reaches (it stays straight), never a finite one.
    """
    return Mechanism("straight truss on a crank", "ground", "bar1", (
        _r("O", "ground", "carrier", (0, 0, 0)),
        _r("A", "carrier", "bar1", (1, 0, 0)),
        _r("B", "bar1", "bar2", (2, 0.5, 0)),
        _r("C", "bar2", "carrier", (3, 1, 0)),
    ))


def _rigid(seed=3):
    rng = np.random.default_rng(seed)
    axis = rng.normal(size=3)
    return Transform(rotation_from_axis_angle(axis / np.linalg.norm(axis), 2.1), rng.normal(size=3) * 50.0)


def _features(m: Mechanism) -> dict[str, tuple[list[np.ndarray], list[np.ndarray]]]:
    """Points and directions fixed in each link (a U joint's first axis in links[0], its second in links[1])."""
    out: dict[str, tuple[list[np.ndarray], list[np.ndarray]]] = {name: ([], []) for name in m.links}
    for j in m.world_joints:
        for side, link in enumerate(j.links):
            points, directions = out[link]
            # R, U, S: the point is fixed in both links; C, H: only in links[0] (links[1]
            # slides along the axis); P, E: the point only locates the joint
            if j.point is not None and (j.type in ("R", "U", "S") or (j.type in ("C", "H") and side == 0)):
                points.append(np.asarray(j.point))
            if j.axis is not None:
                directions.append(np.asarray(j.axis))
            if j.normal is not None:
                directions.append(np.asarray(j.normal))
            if j.axes is not None:
                directions.append(np.asarray(j.axes[side]))
    return out


def rigidity_gap(given: Mechanism, moved: Mechanism) -> float:
    """Largest change, between two poses, of any rigid invariant of any link (over the size of the mechanism).

    Invariants of a link: distances between its points, angles between its
    directions, and the components of its point differences along its
    directions.  A loop that did not close would stretch the link that
    carries the joint closing it; this does not use the loop residual.
    """
    a, b = _features(given), _features(moved)
    size = max(float(np.ptp(np.array([j.point for j in given.world_joints if j.point is not None]), axis=0).max()), 1e-300)
    worst = 0.0
    for link in given.links:
        (pa, da), (pb, db) = a[link], b[link]
        for i in range(len(pa)):
            for k in range(i + 1, len(pa)):
                worst = max(worst, abs(np.linalg.norm(pa[i] - pa[k]) - np.linalg.norm(pb[i] - pb[k])) / size)
                for d in range(len(da)):
                    worst = max(worst, abs(da[d] @ (pa[i] - pa[k]) - db[d] @ (pb[i] - pb[k])) / size)
        for d in range(len(da)):
            for e in range(d + 1, len(da)):
                worst = max(worst, abs(float(da[d] @ da[e] - db[d] @ db[e])))
    return worst


# ---------------------------------------------------------------------------
# the cases of the issue
# ---------------------------------------------------------------------------


def test_flat_four_bar_has_two_instantaneous_dof_and_cannot_move():
    f = finite_mobility(flat_four_bar())
    assert (f.instantaneous_dof, f.instantaneous_mobility) == (2, 2)
    assert f.verdict == "cannot-move"
    assert (f.full_cycle_dof, f.full_cycle_mobility, f.full_cycle_pattern) == (0, 0, "0")
    assert f.instantaneous_only_dof == 2 and not f.branches
    assert f.moved == 0 and len(f.probes) >= 8
    # the obstruction is of second order: the residual left grows like h^2
    for p in f.probes:
        assert p.residuals[0] > 1e-9
    # second route: no first-order motion survives to second order, by a wide margin
    assert f.second_order.obstructed and f.second_order.least_violation > 0.05


def test_folded_parallelogram_is_a_bifurcation_of_two_one_dof_branches():
    f = finite_mobility(folded_parallelogram())
    assert (f.instantaneous_dof, f.instantaneous_mobility) == (2, 2)
    assert f.verdict == "bifurcation"
    assert [b.dimension for b in f.branches] == [1, 1]
    # the parallelogram branch: the coupler translates; the antiparallelogram branch: it rotates
    assert sorted(b.pattern for b in f.branches) == ["1R", "1T"]
    assert (f.full_cycle_dof, f.full_cycle_mobility) == (1, 1)
    # closed-form tangent of the parallelogram branch: relative angles (t, -t, t, -t) at A, B, C, D
    translating = next(b for b in f.branches if b.pattern == "1T")
    expected = np.array([1.0, -1.0, 1.0, -1.0]) / 2.0
    assert abs(abs(float(translating.tangent[:, 0] @ expected)) - 1.0) < 1e-3
    # the two branches leave the pose along different lines, both found by the second-order test
    t1, t2 = (b.tangent[:, 0] for b in f.branches)
    assert abs(float(t1 @ t2)) < 0.9
    assert f.second_order.directions.shape[1] == 2


def test_bennett_has_one_full_cycle_dof_and_keeps_its_link_geometry():
    m = bennett()
    f = finite_mobility(m)
    assert (f.verdict, f.instantaneous_dof, f.full_cycle_dof, f.full_cycle_pattern) == ("full-cycle", 1, 1, "1R")
    # follow the motion far (0.6 rad in steps), then check Bennett's link lengths and twists held
    poses = [m]
    for _ in range(6):
        kin = kinematics(poses[-1])
        d = kin.tangent_space(np.zeros(4))[:, 0]
        closure = kin.close(0.1 * d, constraints=(d[None, :], np.array([0.1])))
        assert closure.converged
        poses.append(kin.mechanism_at(closure.q))

    def common_normals(mech):
        out = []
        js = mech.joints
        for i in range(4):
            a, b = js[i], js[(i + 1) % 4]
            n = np.cross(a.axis, b.axis)
            dist = abs(float(np.dot(np.subtract(b.point, a.point), n / np.linalg.norm(n))))
            out.append((dist, float(np.dot(a.axis, b.axis))))
        return np.array(out)

    assert np.allclose(common_normals(poses[-1]), common_normals(m), atol=1e-10)
    assert rigidity_gap(m, poses[-1]) < 1e-11
    assert abs(float(np.dot(poses[-1].joints[1].axis, m.joints[1].axis))) < 0.999  # it did move


def test_generic_spatial_4r_is_rigid():
    f = finite_mobility(generic_4r())
    assert (f.instantaneous_dof, f.instantaneous_mobility) == (0, 0)
    assert (f.verdict, f.full_cycle_dof, f.full_cycle_mobility) == ("full-cycle", 0, 0)
    assert sample_poses(generic_4r(), 3) == []


def _platform_rotation(m: Mechanism, q: np.ndarray) -> float:
    g = kinematics(m).link_displacements(q)["platform"]
    return float(np.linalg.norm(displacement_log(g)[:3]))


def test_3upu_at_a_constraint_singularity_extra_dof_is_instantaneous_only():
    m = tsai_3upu()
    f = finite_mobility(m)
    assert (f.instantaneous_dof, f.instantaneous_pattern, f.instantaneous_mobility) == (4, "3T1R", 4)
    # the fourth freedom (the rotation) is not a finite one: every branch has 3
    assert f.full_cycle_dof == 3 and f.full_cycle_mobility == 3 and f.instantaneous_only_dof == 1
    # and the pose is where the translational mode meets another operation mode
    # (Zlatanov, Bonev, Gosselin 2002; Walter, Husty 2011)
    assert f.verdict == "bifurcation"
    translational = [b for b in f.branches if b.pattern == "3T"]
    other = [b for b in f.branches if b.pattern != "3T"]
    assert len(translational) == 1 and other
    assert _platform_rotation(m, translational[0].q) < 1e-12
    assert all(_platform_rotation(m, b.q) > 1e-4 for b in other)


def test_3upu_away_from_the_singularity_is_full_cycle_3t():
    f = finite_mobility(tsai_3upu((0.3, 0.2, 1.5)))
    assert (f.verdict, f.instantaneous_pattern, f.full_cycle_pattern, f.full_cycle_mobility) == ("full-cycle", "3T", "3T", 3)


def test_4puu_singular_variant_extra_dof_is_instantaneous_only():
    f = finite_mobility(puu4(singular=True))
    assert (f.instantaneous_dof, f.instantaneous_pattern) == (5, "3T2R")
    assert f.full_cycle_dof == 4 and f.instantaneous_only_dof == 1
    assert "3T1R" in f.full_cycle_pattern.split(" | ")  # the Schönflies motion is one of the branches
    assert f.verdict == "bifurcation"
    generic = finite_mobility(puu4(singular=False))
    assert (generic.verdict, generic.full_cycle_dof, generic.full_cycle_pattern) == ("full-cycle", 4, "3T1R")


def test_a_freedom_infinitesimal_at_every_pose_is_instantaneous_only():
    # nearby poses have the same first-order mobility (2): only the moves tell
    f = finite_mobility(straight_truss_on_crank())
    assert (f.instantaneous_mobility, f.instantaneous_dof) == (2, 2)
    assert (f.verdict, f.full_cycle_mobility, f.full_cycle_dof, f.full_cycle_pattern) == ("instantaneous-only", 1, 1, "1R")
    assert len(f.branches) == 1
    assert 0 < f.moved < len(f.probes)  # moves along the straight chain's sideways freedom fail
    # the branch's tangent is exact: the carrier's turn about O (joint O alone), where the forms vanish
    branch = f.branches[0]
    assert branch.source == "second-order forms" and branch.mobility_nearby == 2
    assert abs(abs(float(branch.tangent[0, 0])) - 1.0) < 1e-12


def test_library_3upu_singular_changes_operation_mode():
    path = MECHANISMS / "3upu_singular.yaml"
    m = mobility.load(path)
    f = finite_mobility(m)
    assert (f.instantaneous_dof, f.instantaneous_pattern) == (4, "3T1R")
    assert (f.verdict, f.full_cycle_dof, f.instantaneous_only_dof) == ("bifurcation", 3, 1)
    assert sorted(b.pattern for b in f.branches) == ["3R", "3T"]
    assert [_platform_rotation(m, b.q) > 1e-4 for b in f.branches] == [b.pattern != "3T" for b in f.branches]


def test_library_4puu_singular_gains_an_instantaneous_rotation_only():
    path = MECHANISMS / "4puu_singular.yaml"
    f = finite_mobility(mobility.load(path))
    assert (f.instantaneous_dof, f.instantaneous_pattern) == (4, "3T1R")
    assert (f.verdict, f.full_cycle_dof, f.full_cycle_pattern, f.instantaneous_only_dof) == ("instantaneous-only", 3, "3T", 1)


# ---------------------------------------------------------------------------
# invariance and robustness
# ---------------------------------------------------------------------------


@pytest.mark.parametrize("build", [flat_four_bar, folded_parallelogram, bennett], ids=["flat", "parallelogram", "bennett"])
def test_verdict_does_not_change_with_scale_or_rigid_motion(build):
    m = build()
    base = finite_mobility(m)
    for other in (transformed(m, Transform.identity(), 1000.0), transformed(m, _rigid(), 1.0)):
        f = finite_mobility(other)
        assert (f.verdict, f.full_cycle_dof, f.full_cycle_mobility, f.full_cycle_pattern) == (
            base.verdict, base.full_cycle_dof, base.full_cycle_mobility, base.full_cycle_pattern)
        assert [b.dimension for b in f.branches] == [b.dimension for b in base.branches]
        assert f.moved == base.moved


def test_spherical_joints_give_the_same_answer_in_any_frame():
    # S joints turn about the global axes, so the joint variables differ between frames; the answer must not
    rssr = Mechanism("RSSR", "ground", "rocker", (
        _r("A", "ground", "crank", (0, 0, 0)),
        Joint("B", "S", ("crank", "coupler"), point=(1.0, 0.0, 0.2)),
        Joint("C", "S", ("coupler", "rocker"), point=(2.5, 1.0, 0.5)),
        _r("D", "rocker", "ground", (3, 0, 0), axis=(0, 1, 0)),
    ))
    for m in (rssr, transformed(rssr, _rigid(5), 1000.0)):
        f = finite_mobility(m)
        assert (f.verdict, f.instantaneous_mobility, f.full_cycle_mobility, f.full_cycle_dof) == ("full-cycle", 2, 2, 1)


def test_geometry_special_only_to_the_rank_tolerance_counts_as_exact():
    m = bennett()
    j = m.joints[2]
    for eps, verdict, dof in ((1e-9, "full-cycle", 1), (1e-6, "full-cycle", 0)):
        axis = np.asarray(j.axis) + eps * np.array([0.3, -0.5, 0.2])
        joints = list(m.joints)
        joints[2] = Joint(j.name, "R", j.links, axis=tuple(axis), point=j.point)
        f = finite_mobility(m.replace(joints=tuple(joints)))
        assert (f.verdict, f.instantaneous_dof, f.full_cycle_dof) == (verdict, dof, dof)


def test_moves_solved_together_are_the_moves_made_one_by_one():
    from mobility.finite.moves import MovePlan, probe, probes
    from mobility.finite.orders import canonical_basis, first_order

    for m in (flat_four_bar(), folded_parallelogram(), tsai_3upu()):
        kin = kinematics(m)
        n = kin.variable_count
        plan = MovePlan.at_given_pose(kin, (1e-3, 1e-2, 5e-2))
        basis = canonical_basis(first_order(kin, np.zeros(n)).tangent)
        candidates = [("basis", basis[:, 0]), ("basis", -basis[:, -1]), ("random", basis @ np.full(basis.shape[1], basis.shape[1] ** -0.5))]
        start = np.zeros(n) if m.name != "four-bar" else 0.01 * basis[:, 0]
        together = probes(plan, start, candidates)
        assert len(together) == len(candidates)
        for p, (source, d) in zip(together, candidates):
            alone = probe(plan, start, source, d)
            assert (p.source, p.moved, p.steps, p.iterations, p.mobility, p.dof) == (alone.source, alone.moved, alone.steps, alone.iterations, alone.mobility, alone.dof)
            assert np.allclose(p.residuals, alone.residuals, rtol=0.0, atol=1e-15)
        # the flat four-bar stops every move at its first step, as one move alone does
        if m.name == "flat four-bar":
            assert all(not p.moved and p.steps == (1e-3,) for p in together)


def test_the_library_check_needs_no_scipy():
    from test_start import heavy, modules_after

    modules = modules_after("from mobility.cli import main\nmain(['check', 'mechanisms'])")
    assert "mobility.finite.full_cycle" in modules and "mobility.actuation" in modules  # the full-cycle and actuation verdicts ran
    assert heavy(modules) == {"networkx"}  # the spanning trees; no scipy (pivoted QR, least squares)


def test_a_second_order_term_at_round_off_passes_every_motion():
    # the Sarrus linkage moves on a straight line: its loops do not open to second order at all; measuring the
    # round-off of the forms against the round-off of the whole term said "obstructed" (by the last bit of the basis)
    from mobility.finite.orders import canonical_basis, first_order, second_order

    kin = kinematics(mobility.load(MECHANISMS / "sarrus.yaml"))
    here = first_order(kin, np.zeros(kin.variable_count))
    for basis in (canonical_basis(here.tangent), here.tangent, -here.tangent, here.tangent + 1e-16):
        second = second_order(kin, basis / np.linalg.norm(basis), np.random.default_rng(0), here.largest_dropped)
        assert not second.obstructed and second.least_violation == 0.0
    f = finite_mobility(mobility.load(MECHANISMS / "sarrus.yaml"))
    assert f.verdict == "full-cycle" and not f.second_order.obstructed


@pytest.mark.parametrize("build", [tsai_3upu, puu4, bennett, folded_parallelogram], ids=["3-UPU", "4-PUU", "bennett", "parallelogram"])
def test_the_moves_tried_do_not_change_with_scale_or_rigid_motion(build):
    # joint variables of R, P and U joints do not change with the frame, so neither may the basis the moves start from,
    # even where a symmetric mechanism ties two joints exactly (the tie goes to the lower variable, not to round-off)
    from mobility.finite.orders import canonical_basis, first_order

    m = build()
    bases = []
    for other in (m, transformed(m, Transform.identity(), 1000.0), transformed(m, _rigid(), 1.0), transformed(m, _rigid(7), 0.01)):
        kin = kinematics(other)
        bases.append(canonical_basis(first_order(kin, np.zeros(kin.variable_count)).tangent))
    assert bases[0].shape[1] >= 1
    for b in bases[1:]:
        assert np.abs(b - bases[0]).max() < 1e-9


def test_results_are_reproducible_for_a_seed():
    a = finite_mobility(folded_parallelogram(), seed=4)
    b = finite_mobility(folded_parallelogram(), seed=4)
    assert [p.residuals for p in a.probes] == [p.residuals for p in b.probes]


@pytest.mark.parametrize("steps", [(0.0, 0.01), (), (-0.1,), (float("nan"), 0.1), ("a",)])
def test_bad_steps_are_refused(steps):
    with pytest.raises(RequestError, match="steps: expected positive numbers"):
        finite_mobility(bennett(), steps=steps)


# ---------------------------------------------------------------------------
# sample_poses
# ---------------------------------------------------------------------------


def test_sample_poses_are_closed_distinct_and_reproducible():
    m = four_bar([(0, 0, 0), (1, 2, 0), (4, 2.5, 0), (5, 0, 0)])
    poses = sample_poses(m, 5, step=0.2, seed=7)
    assert len(poses) == 5
    crank_points = {tuple(np.round(p.joints[1].point, 9)) for p in poses}
    assert len(crank_points) == 5
    for p in poses:
        # link lengths are those of the given pose
        pts = [np.asarray(j.point) for j in p.joints]
        for (i, k), length in {(0, 1): np.sqrt(5), (1, 2): np.sqrt(9.25), (2, 3): np.sqrt(7.25), (3, 0): 5.0}.items():
            assert abs(np.linalg.norm(pts[k] - pts[i]) - length) < 1e-10
        assert mobility.analyze(p).dof == 1
    again = sample_poses(m, 5, step=0.2, seed=7)
    assert all(np.allclose(a.joints[2].point, b.joints[2].point, atol=1e-12) for a, b in zip(poses, again))


def test_sample_poses_follow_scale_and_return_nothing_when_stuck():
    m = tsai_3upu((0.3, 0.2, 1.5))
    poses = sample_poses(m, 3, step=0.1, seed=2)
    scaled = sample_poses(transformed(m, Transform.identity(), 1000.0), 3, step=0.1, seed=2)
    assert len(poses) == len(scaled) == 3
    for p, s in zip(poses, scaled):
        assert np.allclose(1000.0 * np.asarray(p.joints[0].axes[1]), 1000.0 * np.asarray(s.joints[0].axes[1]), atol=1e-8)
        assert np.allclose(1000.0 * np.asarray(p.joints[2].point), s.joints[2].point, atol=1e-8)
        assert mobility.analyze(p).pattern == "3T"
        assert rigidity_gap(m, p) < 1e-11
    assert sample_poses(flat_four_bar(), 4) == []


# ---------------------------------------------------------------------------
# library files, the expected block, the command line
# ---------------------------------------------------------------------------


def _files_with_finite_expectations():
    out = []
    for path in sorted(MECHANISMS.glob("*.yaml")):
        m = mobility.load(path)
        if m.expected is not None and "finite_verdict" in m.expected.extra:
            out.append(path)
    return out


FINITE_FILES = _files_with_finite_expectations()


def test_our_library_files_carry_finite_expectations():
    names = {p.name for p in FINITE_FILES}
    assert {"four_bar_flat.yaml", "parallelogram_change_point.yaml", "spatial_4r_generic.yaml"} <= names


@pytest.mark.parametrize("path", FINITE_FILES, ids=[p.name for p in FINITE_FILES])
def test_library_file_meets_its_finite_expectations(path):
    m = mobility.load(path)
    f = finite_mobility(m)
    values = f.expected_values()
    for key, expected in m.expected.extra.items():
        if key in values:
            assert values[key] == expected, key
    assert f.verdict == m.expected.extra["finite_verdict"]
    assert f.instantaneous_dof == m.expected.dof


def test_library_bennett_is_full_cycle():
    path = MECHANISMS / "bennett.yaml"
    f = finite_mobility(mobility.load(path))
    assert (f.verdict, f.full_cycle_dof, f.full_cycle_pattern) == ("full-cycle", 1, "1R")


def test_finite_verdict_in_expected_is_validated(write_yaml):
    text = (MECHANISMS / "four_bar_flat.yaml").read_text().replace("finite_verdict: cannot-move", "finite_verdict: stuck")
    with pytest.raises(MechanismFileError) as err:
        mobility.load(write_yaml(text))
    assert "expected.finite_verdict" in str(err.value) and "cannot-move" in str(err.value)
    for verdict in VERDICTS:  # the loader accepts exactly the verdicts finite_mobility gives
        mobility.load(write_yaml(text.replace("finite_verdict: stuck", f"finite_verdict: {verdict}")))


def test_cli_analyze_finite_text_and_json(capsys):
    path = str(MECHANISMS / "parallelogram_change_point.yaml")
    assert main(["analyze", path, "--finite"]) == 0
    out = capsys.readouterr().out
    assert "end-effector DOF: 2" in out and "verdict: bifurcation" in out and "branch 2:" in out
    assert main(["analyze", path, "--finite", "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["dof"] == 2
    assert data["finite"]["verdict"] == "bifurcation"
    assert data["finite"]["full_cycle"] == {"dof": 1, "pattern": "1T | 1R", "mobility": 1}
    assert len(data["finite"]["branches"]) == 2
    assert main(["analyze", path]) == 0
    assert "verdict" not in capsys.readouterr().out  # only on request


def test_cli_analyze_finite_markdown(capsys):
    assert main(["analyze", str(MECHANISMS / "four_bar_flat.yaml"), "--finite", "--format", "md"]) == 0
    out = capsys.readouterr().out
    assert "## Finite motion" in out and "verdict: cannot-move" in out


def test_finite_report_names_the_obstruction():
    text = finite_report(finite_mobility(flat_four_bar()))
    assert "verdict: cannot-move" in text and "second order" in text and "obstructed" in text


def test_a_pose_where_only_the_pattern_is_special_says_so():
    # Two R-R-S limbs tied by an S-S bridge: 1T2R at this pose, 3R at every pose nearby (same DOF 3, mobility 4).
    z, x, y = (0, 0, 1), (1, 0, 0), (0, 1, 0)
    m = Mechanism("R-R-S pair with an S-S bridge", "ground", "ee", (
        Joint("A1", "R", ("ground", "a1"), axis=z, point=(0, 0, 0)), Joint("A2", "R", ("a1", "a2"), axis=x, point=(0, 100, 0)),
        Joint("A3", "S", ("a2", "ee"), point=(0, 100, 200)),
        Joint("B1", "R", ("ground", "b1"), axis=z, point=(300, 0, 0)), Joint("B2", "R", ("b1", "b2"), axis=y, point=(300, 100, 0)),
        Joint("B3", "S", ("b2", "ee"), point=(300, 100, 200)),
        Joint("X1", "S", ("a2", "bridge"), point=(0, 150, 100)), Joint("X2", "S", ("bridge", "b2"), point=(300, 50, 120)),
    ))
    f = finite_mobility(m)
    assert (f.instantaneous_dof, f.instantaneous_pattern, f.instantaneous_mobility) == (3, "1T2R", 4)
    assert (f.verdict, f.full_cycle_dof, f.full_cycle_pattern, f.full_cycle_mobility) == ("full-cycle", 3, "3R", 4)
    assert "but not the pattern: 3R at nearby poses, 1T2R at this one" in f.explanation
    # the nearby pattern, by the screw route at a sampled pose (a second route to the same answer)
    assert {mobility.analyze(p).pattern for p in sample_poses(m, 3, step=0.05)} == {"3R"}


def test_a_wrist_in_gimbal_lock_is_singular_for_the_end_effector_only():
    # ZYZ wrist with its first and last axes in line: 2R at this pose, 3R at every other pose of its one
    # branch.  Moves about the locked axes alone stay on the singular locus; the branch is measured at
    # its most regular pose reached, so the full-cycle DOF is the generic 3.
    axes = ((0.0, 0.0, 1.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0))
    links = ("ground", "l1", "l2", "tool")
    wrist = Mechanism(
        "ZYZ wrist", "ground", "tool",
        tuple(Joint(f"J{i + 1}", "R", (links[i], links[i + 1]), axis=a, point=(0.0, 0.0, float(i))) for i, a in enumerate(axes)),
    )
    here = mobility.analyze(wrist)
    assert (here.dof, here.pattern, here.mobility) == (2, "2R", 3)
    fm = finite_mobility(wrist)
    assert (fm.instantaneous_dof, fm.full_cycle_dof, fm.full_cycle_pattern, fm.full_cycle_mobility) == (2, 3, "3R", 3)
    assert "the pose is singular for the end effector, not for the mechanism" in fm.explanation
    tilted = kinematics(wrist).mechanism_at(np.array([0.0, 0.2, 0.0]))  # the second route: the screws one pose away
    assert mobility.analyze(tilted).dof == 3
    swept = mobility.sweep(wrist, ["J2=-10:10:5"])  # a third: the batched screws across the lock
    assert swept.dof.tolist() == [3, 3, 2, 3, 3]
    assert [(p.values, p.reasons) for p in swept.singular] == [((0.0,), ("the end effector loses 1 freedom while the mechanism still moves (a serial singularity): 2 DOF (2R)",))]
