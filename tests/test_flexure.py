"""Flexure mechanisms: compliance, freedom and constraint spaces, linear actuators.

The three-rod flexure is the example of Li, Shan, Yu and Ke, "Actuation Spaces
Synthesis of Lower-Mobility Parallel Mechanisms Based on Screw Theory" (Chin. J.
Mech. Eng., 2021): l = 82 mm, r = 1.5 mm, E = 70 GPa, nu = 0.346, R = 102 mm,
rods tilted 45 degrees; their axes meet at O = (0, 0, 102 mm).
"""

from __future__ import annotations

import json
import math
import re
import warnings
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest
from builders import ONE_WIRE_FLEXURE

from mobility.actuation import SINGULAR, VALID
from mobility.cli import main
from mobility.errors import MechanismError, MechanismFileError, RequestError
from mobility.flexure import (
    FlexureMechanism,
    ForceLine,
    Material,
    Rod,
    check_force_lines,
    compliance_matrix,
    enumerate_force_lines,
    flexure_spaces,
    line_set_type,
    load_flexure,
    loads_flexure,
    normalised_energy_form,
    rod_compliance,
)
from mobility.core.screws import SWAP, adjoint, same_subspace
from mobility.core.tolerance import Tolerance
from mobility.core.transforms import rotation_from_axis_angle

ROOT = Path(__file__).resolve().parents[1]
FILE = ROOT / "examples" / "flexure" / "three_rod.yaml"
TEXT = FILE.read_text(encoding="utf-8")
O = np.array([0.0, 0.0, 102.0])
ALU = Material("aluminium", 70e9, 0.346)


@pytest.fixture(scope="module")
def flexure() -> FlexureMechanism:
    return load_flexure(FILE)


def with_parameters(text: str, **values: float) -> str:
    for key, value in values.items():
        text, n = re.subn(rf"\n  {key}: [^\n#]*", f"\n  {key}: {value!r} ", text, count=1)
        assert n == 1, key
    return text


# ---------------------------------------------------------------------------
# compliance of one rod and of networks
# ---------------------------------------------------------------------------


def test_rod_compliance_equals_the_integral_of_its_sections():
    """A beam is a continuous series of thin sections: C_tip = integral of Ad c Ad^-1 ds."""
    length, radius, e, nu = 0.082, 0.0015, 70e9, 0.346
    area, inertia = math.pi * radius**2, math.pi * radius**4 / 4
    g = e / (2 * (1 + nu))
    per_length = np.zeros((6, 6))  # twist per unit length of a section under a wrench at it
    per_length[0, 3] = per_length[1, 4] = 1 / (e * inertia)
    per_length[2, 5] = 1 / (g * 2 * inertia)
    per_length[5, 2] = 1 / (e * area)
    nodes, weights = np.polynomial.legendre.leggauss(8)  # exact: the integrand is quadratic in s
    total = np.zeros((6, 6))
    for x, w in zip(nodes, weights):
        s = 0.5 * length * (x + 1)
        to_tip = adjoint(np.eye(3), np.array([0.0, 0.0, s - length]))  # section frame -> tip frame
        total += 0.5 * length * w * to_tip @ per_length @ np.linalg.inv(to_tip)
    assert np.allclose(rod_compliance(length, radius, e, nu), total, rtol=1e-12, atol=0)


def test_rod_compliance_is_symmetric_in_the_energy_form_and_positive():
    q = SWAP @ rod_compliance(0.05, 0.001, 200e9, 0.3)
    assert np.allclose(q, q.T, rtol=0, atol=1e-15 * np.abs(q).max())
    assert np.all(np.linalg.eigvalsh(q) > 0)


def _rod(name, start, axis, bodies=("g", "s"), length=0.08, radius=0.001):
    return Rod(name, bodies, start, axis, length, radius, ALU)


def test_rods_in_parallel_add_stiffnesses_and_in_series_add_compliances():
    r1 = _rod("a", (0.0, 0.0, 0.0), (0.0, 0.3, 1.0))
    r2 = _rod("b", (0.05, 0.0, 0.0), (-0.2, 0.1, 1.0))
    c1 = compliance_matrix(FlexureMechanism("1", "g", "s", (r1,)))
    c2 = compliance_matrix(FlexureMechanism("2", "g", "s", (r2,)))
    both = compliance_matrix(FlexureMechanism("1+2", "g", "s", (r1, r2)))
    assert np.allclose(both, np.linalg.inv(np.linalg.inv(c1) + np.linalg.inv(c2)), rtol=1e-9, atol=0)
    s1 = replace(r1, bodies=("g", "mid"))
    s2 = replace(r2, bodies=("mid", "s"))
    chain = compliance_matrix(FlexureMechanism("1 then 2", "g", "s", (s1, s2)))
    assert np.allclose(chain, c1 + c2, rtol=1e-9, atol=1e-12 * np.abs(c1 + c2).max())


def test_one_rod_in_the_global_frame_is_the_adjoint_of_its_local_compliance():
    rod = _rod("a", (0.01, 0.02, 0.0), (1.0, 0.0, 1.0))
    end = np.array(rod.start) + rod.length * np.array(rod.axis)
    # any frame at the end with z along the rod will do: the section is round
    z = np.array(rod.axis)
    x = np.cross([0.0, 1.0, 0.0], z)
    x /= np.linalg.norm(x)
    ad = adjoint(np.column_stack([x, np.cross(z, x), z]), end)
    local = rod_compliance(rod.length, rod.radius, ALU.E, ALU.nu)
    expected = ad @ local @ np.linalg.inv(ad)
    assert np.allclose(compliance_matrix(FlexureMechanism("one", "g", "s", (rod,))), expected, rtol=1e-9, atol=1e-12 * np.abs(expected).max())


# ---------------------------------------------------------------------------
# the paper's three-rod flexure
# ---------------------------------------------------------------------------


def test_three_rod_flexure_has_three_rotations_about_O_and_three_forces_through_it(flexure):
    spaces = flexure_spaces(flexure)
    assert (spaces.dof, spaces.pattern) == (3, "3R") and not spaces.warnings
    assert np.all(spaces.eigenvalues[:3] > 0.5) and np.all(spaces.eigenvalues[3:] < 0.01)  # two clusters
    L = spaces.length
    assert spaces.freedom_translations.shape == (0, 3)
    for w_v in spaces.freedom_twists:  # velocity of O under each freedom twist: ~0
        w, v = w_v[:3], w_v[3:]
        assert np.linalg.norm(v + np.cross(w, O)) < 2e-3 * L * np.linalg.norm(w)
    for f_m in spaces.constraint_wrenches:  # moment of each constraint wrench about O: ~0
        f, m = f_m[:3], f_m[3:]
        assert np.linalg.norm(m - np.cross(O, f)) < 2e-3 * L * np.linalg.norm(f)
    # as subspaces, in the normalised coordinates, against the ideal ones
    c, L = flexure.normalisation().centre, flexure.normalisation().length
    ideal_forces = np.array([np.concatenate([e, np.cross(O - c, e) / L]) for e in np.eye(3)]).T
    ideal_rotations = ideal_forces  # a rotation about O has the coordinates of a force through O
    loose = Tolerance(rank=0.01, near_singular=0.03)
    norm_rows = lambda rows: np.array([np.concatenate([r[:3], (r[3:] - np.cross(c, r[:3])) / L]) for r in rows]).T  # noqa: E731
    assert same_subspace(norm_rows(spaces.constraint_wrenches), ideal_forces, loose)
    assert same_subspace(norm_rows(spaces.freedom_twists), ideal_rotations, loose)
    assert not same_subspace(norm_rows(spaces.constraint_wrenches), ideal_forces)  # a real flexure is not ideal


def _offset_from_O(r: float) -> float:
    text = with_parameters(TEXT, r=r)
    spaces = flexure_spaces(loads_flexure(text))
    return max(np.linalg.norm(t[3:] + np.cross(t[:3], O)) / np.linalg.norm(t[:3]) for t in spaces.freedom_twists)


def test_rotation_per_unit_couple_is_frame_free_and_the_z_rotation_is_the_softest(flexure):
    """docs/actuation.md: the couple block of C (6.48e-3, 6.48e-3, 9.46e-3 rad/(N m)) against the relative compliances (1, 1, 0.832).

    Second route: each rod's compliance at its midpoint (its centre of elasticity, where the
    bending, axial and torsion terms are uncoupled: l^3/12EI, l/EA, l/EI, l/GJ), moved to the
    origin by the adjoint, the stiffnesses summed.
    """
    area, inertia = math.pi * 0.0015**2, math.pi * 0.0015**4 / 4
    g = ALU.E / (2 * (1 + ALU.nu))
    mid = np.zeros((6, 6))
    mid[3, 0] = mid[4, 1] = 0.082**3 / (12 * ALU.E * inertia)
    mid[5, 2] = 0.082 / (ALU.E * area)
    mid[0, 3] = mid[1, 4] = 0.082 / (ALU.E * inertia)
    mid[2, 5] = 0.082 / (g * 2 * inertia)
    stiffness = np.zeros((6, 6))
    for e in flexure.elements:
        z = np.asarray(e.axis) / np.linalg.norm(e.axis)
        x = np.cross([0.0, 0.0, 1.0], z)
        x /= np.linalg.norm(x)
        ad = adjoint(np.column_stack([x, np.cross(z, x), z]), (np.asarray(e.start) + 0.5 * e.length * z) * 1e-3)
        stiffness += np.linalg.inv(ad @ mid @ np.linalg.inv(ad))
    expected = np.linalg.inv(stiffness)
    c = compliance_matrix(flexure)
    assert np.allclose(c, expected, rtol=1e-9, atol=1e-9 * np.abs(expected).max())
    couple = np.diag(c[:3, 3:])
    assert couple == pytest.approx([6.4752e-3, 6.4752e-3, 9.4574e-3], rel=1e-4)
    assert couple[2] / couple[0] == pytest.approx(1.46, abs=0.005)
    moved = adjoint(rotation_from_axis_angle(np.array([0.0, 0.0, 1.0]), 0.3), np.array([0.4, -0.25, 0.09]))
    assert np.allclose(np.diag((moved @ c @ np.linalg.inv(moved))[:3, 3:]), [couple[1], couple[0], couple[2]], rtol=1e-9)
    assert flexure_spaces(flexure).eigenvalues[:3] == pytest.approx([1.0, 1.0, 0.832], abs=5e-4)


def test_freedoms_approach_the_ideal_rotations_about_O_as_the_rods_get_slender():
    # The deviation comes from the rods' bending stiffness: it scales as (r / l)^2.
    wide, thin = _offset_from_O(1.5), _offset_from_O(0.75)
    assert 0.0 < thin < wide
    assert wide / thin == pytest.approx(4.0, rel=0.05)


def test_vertical_compliance_through_O_is_that_of_three_axial_rods(flexure):
    c = compliance_matrix(flexure)
    wrench = np.array([0, 0, 1.0, 0, 0, 0])  # 1 N along z through the origin, on the z axis like O
    t = c @ wrench
    down = (t[3:] + np.cross(t[:3], O * 1e-3))[2]  # displacement of O (m)
    axial = ALU.E * math.pi * 0.0015**2 / 0.082
    expected = 1.0 / (3 * axial * math.cos(math.radians(45)) ** 2)
    assert down == pytest.approx(expected, rel=0.01)
    assert down < expected  # bending adds a little stiffness


@pytest.mark.parametrize("threshold", [0.002, 0.01, 0.1, 0.5])
def test_any_threshold_between_the_two_clusters_gives_the_same_spaces(flexure, threshold):
    ref = flexure_spaces(flexure)
    spaces = flexure_spaces(flexure, threshold)
    assert spaces.dof == 3 and not spaces.warnings
    assert spaces.gap == pytest.approx((ref.eigenvalues[2], ref.eigenvalues[3]))
    assert np.allclose(spaces.freedom_twists, ref.freedom_twists) and np.allclose(spaces.constraint_wrenches, ref.constraint_wrenches)


def test_a_threshold_inside_a_cluster_splits_it_and_warns(flexure):
    high = flexure_spaces(flexure, 0.9)  # between 1 and 0.83
    assert high.dof == 2 and "does not sit in a clear gap" in high.warnings[0]
    low = flexure_spaces(flexure, 0.0015)  # between 0.00157 and 0.00138
    assert low.dof == 5 and low.warnings
    assert flexure_spaces(flexure, 1e-4).dof == 6


# ---------------------------------------------------------------------------
# linear actuators
# ---------------------------------------------------------------------------


def test_tangential_actuators_are_valid(flexure):
    check = check_force_lines(flexure)  # t1, t2, t3 are marked actuated
    assert [i.name for i in check.inputs] == ["t1", "t2", "t3"]
    assert check.verdict == VALID and check.rank == 6 and check.conditioning > 0.3
    assert check.kind == "flexure" and check.dof == 3


def _rotation_axis(check) -> tuple[np.ndarray, np.ndarray]:
    (rot,) = check.uncontrolled_rotations
    assert rot.kind == "rotation" and check.uncontrolled_translations.shape == (0, 3)
    return rot.axis, rot.point


def _distance(point, line_point, direction) -> float:
    return float(np.linalg.norm(np.cross(np.subtract(point, line_point), direction)))


def test_forces_meeting_at_a_point_of_the_z_axis_leave_the_rotation_about_it(flexure):
    check = check_force_lines(flexure, ["c1", "c2", "c3"])
    assert check.verdict == SINGULAR and check.rank == 5 and check.conditioning == 0.0
    axis, point = _rotation_axis(check)
    assert abs(abs(axis[2]) - 1) < 1e-6 and np.linalg.norm(point[:2]) < 1e-6


def test_forces_meeting_at_a_point_off_the_axes_leave_the_rotation_about_the_line_to_O(flexure):
    # Three forces through P lose every moment about the line OP, wherever P is:
    # concurrent force lines never actuate a rotation about a point.
    check = check_force_lines(flexure, ["e1", "e2", "e3"])
    assert check.verdict == SINGULAR
    axis, point = _rotation_axis(check)
    p = np.array([30.0, 20.0, 90.0])
    direction = (p - O) / np.linalg.norm(p - O)
    assert abs(abs(axis @ direction) - 1) < 1e-3
    assert _distance(O, point, axis) < 0.5 and _distance(p, point, axis) < 0.5


def test_parallel_forces_leave_the_rotation_about_their_direction(flexure):
    check = check_force_lines(flexure, ["v1", "v2", "v3"])
    assert check.verdict == SINGULAR
    axis, point = _rotation_axis(check)
    assert abs(abs(axis[2]) - 1) < 1e-6 and _distance(O, point, axis) < 1e-6


def test_skew_forces_meeting_a_line_that_misses_O_are_valid(flexure):
    assert line_set_type([a for a in flexure.actuators if a.name[0] == "s"]) == "general"
    check = check_force_lines(flexure, ["s1", "s2", "s3"])
    assert check.verdict == VALID and check.conditioning > 0.05


def test_a_force_through_O_lies_in_the_constraint_space(flexure):
    check = check_force_lines(flexure, ["o1", "t1", "t2"])
    assert check.verdict == SINGULAR
    assert [i.in_constraint_space for i in check.inputs] == [True, False, False]


def _centre(spaces) -> np.ndarray:
    """The point nearest every freedom rotation axis (where the flexure turns about)."""
    rows, rhs = [], []
    for r in spaces.freedom_rotations:
        p = np.eye(3) - np.outer(r.axis, r.axis)
        rows.append(p)
        rhs.append(p @ r.point)
    return np.linalg.lstsq(np.vstack(rows), np.concatenate(rhs), rcond=None)[0]


def test_random_line_sets_follow_the_geometric_rule(flexure):
    """Three force lines are invalid exactly when one line through the centre meets them all."""
    spaces = flexure_spaces(flexure)
    centre = _centre(spaces)
    assert np.linalg.norm(centre - O) < 2e-3 * spaces.length  # the rods' bending moves it a little
    rng = np.random.default_rng(7)

    def lines(points, directions):
        return [ForceLine(f"x{k}", tuple(p), tuple(d)) for k, (p, d) in enumerate(zip(points, directions))]

    def lost_axis(found):
        (rot,) = found.uncontrolled_rotations
        return rot.axis, rot.point

    for _ in range(10):
        # concurrent at P: the rotation about the line from the centre to P is lost
        p = centre + rng.uniform(-80, 80, size=3)
        found = check_force_lines(flexure, [], lines=lines([p] * 3, rng.normal(size=(3, 3))))
        axis, point = lost_axis(found)
        assert found.verdict == SINGULAR and _distance(centre, point, axis) < 1e-6 and _distance(p, point, axis) < 1e-6
        # parallel: the rotation about the parallel through the centre is lost
        d = rng.normal(size=3)
        found = check_force_lines(flexure, [], lines=lines(centre + rng.uniform(-80, 80, size=(3, 3)), [d] * 3))
        axis, point = lost_axis(found)
        assert found.verdict == SINGULAR and abs(abs(axis @ d) / np.linalg.norm(d) - 1) < 1e-9 and _distance(centre, point, axis) < 1e-6
        # each meeting one line through the centre: the rotation about that line is lost
        u = rng.normal(size=3)
        u /= np.linalg.norm(u)
        found = check_force_lines(flexure, [], lines=lines([centre + rng.uniform(-60, 60) * u for _ in range(3)], rng.normal(size=(3, 3))))
        axis, point = lost_axis(found)
        assert found.verdict == SINGULAR and abs(abs(axis @ u) - 1) < 1e-6 and _distance(centre, point, axis) < 1e-6
    # general lines: valid when their moments about the centre are independent (an ideal-model route)
    clear = 0
    for _ in range(30):
        points, directions = centre + rng.uniform(-80, 80, size=(3, 3)), rng.normal(size=(3, 3))
        moments = np.cross((points - centre) / spaces.length, directions / np.linalg.norm(directions, axis=1)[:, None])
        sv = np.linalg.svd(moments, compute_uv=False)
        if sv[-1] > 0.1 * sv[0]:
            clear += 1
            assert check_force_lines(flexure, [], lines=lines(points, directions)).verdict == VALID
    assert clear >= 15


@pytest.mark.parametrize(
    "points, verdict",
    [
        ([(30, 20, -50)] * 3, SINGULAR),  # Eq. 29: concurrent off the axes (the paper: valid)
        ([(0, 10, -50), (20, 0, -50), (20, 10, 0)], SINGULAR),  # Eq. 34 with x1 y3 = y1 x3: the lines meet at (20, 10, -50)
        ([(0, 10, -50), (20, 0, -50), (20, 25, 0)], VALID),  # Eq. 34 otherwise
        ([(0, -10, -20), (-10, 0, -10), (-20, -10, 0)], SINGULAR),  # Eq. 35 with z1 x2 y3 = y1 z2 x3, pairwise skew
        ([(0, -20, -10), (-10, 0, -30), (-10, -10, 0)], VALID),  # Eq. 35 otherwise
    ],
)
def test_the_papers_table_3_line_sets_follow_the_determinant_of_their_moments(flexure, points, verdict):
    """Forces along x, y, z through the points (about the flexure's centre): det[p_i x d_i] decides, not the paper's conditions."""
    centre = _centre(flexure_spaces(flexure))
    directions = np.eye(3)
    lines = [ForceLine(f"a{k}", tuple(centre + np.asarray(p, float)), tuple(d)) for k, (p, d) in enumerate(zip(points, directions))]
    determinant = np.linalg.det(np.cross(np.asarray(points, float), directions))
    assert (abs(determinant) > 1.0) == (verdict == VALID)
    assert check_force_lines(flexure, [], lines=lines).verdict == verdict


def test_enumeration_groups_the_candidate_sets_by_geometry(flexure):
    found = enumerate_force_lines(flexure)
    groups = {g.type: (g.valid, g.total) for g in found.groups}
    assert groups["concurrent"][0] == 0 and groups["parallel"] == (0, 1)
    assert groups["concurrent"][1] >= 2  # c1-c3 and e1-e3
    assert groups["general"][0] > 0
    by_inputs = {c.inputs: c for c in found.combinations}
    assert by_inputs[("t1", "t2", "t3")].verdict == VALID and by_inputs[("t1", "t2", "t3")].type == "coplanar"
    assert by_inputs[("c1", "c2", "c3")].type == "concurrent" and by_inputs[("e1", "e2", "e3")].type == "concurrent"
    assert all(c.verdict != VALID for c in found.combinations if "o1" in c.inputs)
    valid = [float(f"{c.conditioning:.12g}") for c in found.valid]  # ties at round-off fall to the input names
    assert valid == sorted(valid, reverse=True) and found.combinations[: len(valid)] == found.valid


# ---------------------------------------------------------------------------
# invariance
# ---------------------------------------------------------------------------


def test_millimetres_and_gigapascals_or_metres_and_pascals_give_the_same_answers(flexure):
    text = with_parameters(TEXT, l=0.082, r=0.0015, R=0.102, px=0.030, py=0.020, pz=0.090, d=0.040)
    text = text.replace("units: {length: mm, modulus: GPa, angle: deg}", "units: {length: m, modulus: Pa, angle: deg}")
    text = text.replace("{E: 70, nu: 0.346}", "{E: 70.0e9, nu: 0.346}")
    metres = loads_flexure(text)
    a, b = flexure_spaces(flexure), flexure_spaces(metres)
    assert np.allclose(a.eigenvalues, b.eigenvalues, rtol=1e-9, atol=1e-15)
    assert np.allclose(a.compliance, b.compliance, rtol=1e-9, atol=1e-12 * np.abs(a.compliance).max())
    assert a.length == pytest.approx(1000 * b.length)
    for ra, rb in zip(a.freedom_rotations, b.freedom_rotations):
        assert np.allclose(ra.axis, rb.axis, atol=1e-9) and np.allclose(ra.point, 1000 * rb.point, atol=1e-6)
    for names in (["t1", "t2", "t3"], ["s1", "s2", "s3"], ["c1", "c2", "c3"], ["e1", "e2", "e3"], ["v1", "v2", "v3"]):
        ca, cb = check_force_lines(flexure, names), check_force_lines(metres, names)
        assert ca.verdict == cb.verdict and ca.conditioning == pytest.approx(cb.conditioning, rel=1e-9, abs=1e-12)


def test_moving_the_flexure_rigidly_moves_its_spaces(flexure):
    rot = rotation_from_axis_angle(np.array([2.0, -1.0, 2.0]) / 3.0, 1.1)
    t = np.array([400.0, -250.0, 90.0])
    elements = tuple(replace(e, start=tuple(rot @ e.start + t), axis=tuple(rot @ e.axis)) for e in flexure.elements)
    actuators = tuple(replace(a, point=tuple(rot @ a.point + t), direction=tuple(rot @ a.direction)) for a in flexure.actuators)
    moved = replace(flexure, elements=elements, actuators=actuators)
    a, b = flexure_spaces(flexure), flexure_spaces(moved)
    assert np.allclose(a.eigenvalues, b.eigenvalues, rtol=1e-9)
    centre = rot @ O + t
    for w_v in b.freedom_twists:
        assert np.linalg.norm(w_v[3:] + np.cross(w_v[:3], centre)) < 2e-3 * b.length * np.linalg.norm(w_v[:3])
    for names in (["t1", "t2", "t3"], ["c1", "c2", "c3"], ["s1", "s2", "s3"]):
        ca, cb = check_force_lines(flexure, names), check_force_lines(moved, names)
        assert ca.verdict == cb.verdict and ca.conditioning == pytest.approx(cb.conditioning, rel=1e-9, abs=1e-12)


# ---------------------------------------------------------------------------
# documents and command line
# ---------------------------------------------------------------------------


GOOD = ONE_WIRE_FLEXURE


@pytest.mark.parametrize(
    "old, new, where",
    [
        ("radius: 1,", "radius: -1,", "w.yaml:8: elements[0].radius: expected a positive number"),
        ("material: steel}", "material: brass}", "w.yaml:8: elements[0].material: unknown material 'brass'"),
        ("length: 100,", "lenght: 100,", "w.yaml:8: elements[0].lenght: unknown key in a flexure element (did you mean 'length'?)"),
        ("length: mm", "length: furlong", "w.yaml:2: units.length: expected one of"),
        ("nu: 0.3", "nu: 0.7", "w.yaml:6: materials.steel.nu: expected Poisson's ratio in (-1, 0.5)"),
        ("type: rod", "type: blade", "w.yaml:8: elements[0].type: unknown flexure element type 'blade'"),
        ("bodies: [base, stage]", "bodies: [base, base]", "w.yaml:8: elements[0].bodies: an element must join two different bodies"),
        ("end_effector: stage", "end_effector: table", "w.yaml:4: end_effector: body 'table' is not joined by any element"),
        ("name: one wire", "name: true", "w.yaml:1: name: expected a non-empty string, got true"),
        ("name: one wire", "description: no name", "w.yaml:1: name: missing required key"),
        ("radius: 1,", "", "w.yaml:8: elements[0].radius: missing required key of a flexure element"),
        ("steel: {E: 200, nu: 0.3}", "steel: {E: 200}", "w.yaml:6: materials.steel.nu: missing required key of a material"),
    ],
)
def test_bad_documents_are_one_line_errors_with_file_line_and_key(old, new, where):
    assert old in GOOD
    with pytest.raises(MechanismFileError) as info:
        loads_flexure(GOOD.replace(old, new), file="w.yaml")
    assert str(info.value).startswith(where)
    assert "\n" not in str(info.value)


def test_a_body_held_by_nothing_is_an_error():
    text = GOOD + "  - {name: w2, type: rod, bodies: [stage, arm], axis: [0, 0, 1], length: 10, radius: 1, material: steel}\n"
    text += "  - {name: w3, type: rod, bodies: [flag, pole], axis: [0, 0, 1], length: 10, radius: 1, material: steel}\n"
    with pytest.raises(MechanismFileError, match="w.yaml:7: elements: bodies not connected to the ground 'base': flag, pole"):
        loads_flexure(text, file="w.yaml")


@pytest.mark.parametrize(
    "build, key",
    [
        (lambda: Rod("w", ("g", "s"), "abc", (0, 0, 1), 0.1, 0.001, ALU), "point"),
        (lambda: Rod("w", ("g", "s"), (0, 0, 0), (0, 0, 1), 0.1, 0.001, "aluminium"), "material"),
        (lambda: Rod("w", ("g", "s"), (0, 0, 0), (0, 0, 1), "long", 0.001, ALU), "length"),
        (lambda: Material("m", 70e9, "soft"), "nu"),
        (lambda: ForceLine("f", (0, 0, 0), (0, 0, 0)), "direction"),
        (lambda: FlexureMechanism("m", "g", "s", (Rod("w", ("g", "s"), (0, 0, 0), (0, 0, 1), 0.1, 0.001, ALU),), threshold="x"), "threshold"),
    ],
)
def test_bad_descriptions_in_code_are_mechanism_errors_naming_the_key(build, key):
    with pytest.raises(MechanismError) as info:
        build()
    assert info.value.key == key


def test_bad_requests_are_request_errors(flexure):
    for threshold in (0.0, 1.5):
        with pytest.raises(RequestError, match="threshold must lie between 0 and 1"):
            flexure_spaces(flexure, threshold)
    with pytest.raises(RequestError, match="k must be non-negative"):
        enumerate_force_lines(flexure, -1)
    with pytest.raises(MechanismError, match="unknown actuator 'z9'"):
        check_force_lines(flexure, ["t1", "z9"])


def test_normalised_energy_form_is_the_compliance_seen_from_the_centre_in_units_of_L(flexure):
    # Second route: move the compliance to the centre c by the adjoint and scale lengths by L,
    # then compare with the function's Q = SWAP N C N^-1.
    c = compliance_matrix(flexure)
    q, norm = normalised_energy_form(flexure, c)
    centre, length = norm.centre * 1e-3, norm.length * 1e-3  # the document is in mm, C in SI
    to_centre = adjoint(np.eye(3), -centre)  # screw coordinates about the origin -> about c
    scale = np.diag([1.0, 1, 1, 1 / length, 1 / length, 1 / length])
    expected = SWAP @ scale @ to_centre @ c @ np.linalg.inv(to_centre) @ np.linalg.inv(scale)
    assert np.allclose(q, expected, rtol=1e-9, atol=1e-12 * np.abs(expected).max())
    assert np.allclose(q, q.T, rtol=0, atol=1e-12 * np.abs(q).max())
    values = np.sort(np.linalg.eigvalsh(q))[::-1]
    assert np.allclose(values / values[0], flexure_spaces(flexure).eigenvalues, rtol=1e-9, atol=1e-15)


def test_cli_bad_threshold_is_one_line_with_status_2(capsys):
    assert main(["actuation", str(FILE), "--threshold", "1.5"]) == 2
    err = capsys.readouterr().err.strip()
    assert err == "mobility: --threshold must lie between 0 and 1"


def test_cli_flexure_report_json_and_enumeration(capsys):
    assert main(["actuation", str(FILE)]) == 0
    out = capsys.readouterr().out
    assert "freedom space: 3 DOF (3R)" in out and "verdict: VALID" in out and "threshold 0.01" in out
    assert main(["actuation", str(FILE), "--inputs", "v1,v2,v3"]) == 1
    assert "ACTUATION-SINGULAR" in capsys.readouterr().out
    assert main(["actuation", str(FILE), "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["spaces"]["dof"] == 3 and data["actuation"]["verdict"] == "valid" and len(data["spaces"]["eigenvalues"]) == 6
    assert main(["actuation", str(FILE), "--enumerate", "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["enumeration"]["kind"] == "flexure" and data["enumeration"]["k"] == 3
    assert main(["actuation", str(FILE), "--threshold", "0.9"]) == 1  # two freedoms for three inputs: redundant
    assert "does not sit in a clear gap" in capsys.readouterr().out


def test_cli_rejects_poses_for_a_flexure(capsys):
    assert main(["actuation", str(FILE), "--pose", str(FILE)]) == 2
    assert "rigid mechanisms only" in capsys.readouterr().err



@pytest.mark.parametrize("length, radius, expected", [
    ("100", "1e-100", "8: elements[0].radius: radius 1e-100 is less than 1e-06 of the rod's length 100"),
    ("100", "1e-80", "8: elements[0].radius: radius 1e-80 is less than 1e-06"),
    ("1e-300", "1e-301", "8: elements[0]: the compliance of 'w1' (length 1e-300, radius 1e-301, E 2e+11) is beyond the range of double precision"),
])
def test_rods_beyond_double_precision_are_refused_at_their_line(tmp_path, capsys, length, radius, expected):
    path = tmp_path / "rod.yaml"
    path.write_text(GOOD.replace("length: 100, radius: 1,", f"length: {length}, radius: {radius},"))
    assert main(["actuation", str(path)]) == 2
    err = capsys.readouterr().err
    assert err == f"mobility: {path}:{expected}" + err[len(f"mobility: {path}:{expected}"):] and err.count("\n") == 1, err
    path.write_text(GOOD)  # the same rod, of a physical size: analysed
    status = main(["actuation", str(path)])
    assert status in (0, 1) and "compliance eigenvalues" in capsys.readouterr().out


def test_directions_of_any_finite_size_are_directions(tmp_path):
    # A rod's axis and an actuator's direction are directions: 1e200 times them is the same document
    # (their squared norms overflowed, leaving a zero axis, numpy warnings and an unrelated error).
    text = FILE.read_text()
    big = text.replace('axis: ["-sind(tilt)", 0, "cosd(tilt)"]', 'axis: ["-1e200*sind(tilt)", 0, "1e200*cosd(tilt)"]')
    big = big.replace("direction: [0, 1, 0], actuated: true", "direction: [0, 1e300, 0], actuated: true")
    assert big.count("1e200") == 6 and big.count("1e300") == 3
    path = tmp_path / "big.yaml"
    path.write_text(big)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        mine, theirs = load_flexure(path), load_flexure(FILE)
        assert np.abs(np.array([e.axis for e in mine.elements]) - [e.axis for e in theirs.elements]).max() < 1e-15
        a, b = check_force_lines(mine), check_force_lines(theirs)
    assert a.verdict == b.verdict == VALID and a.conditioning == pytest.approx(b.conditioning, rel=1e-12)


@pytest.mark.parametrize("old, new, key, words", [
    ("modulus: GPa", "modulus: [GPa]", "units.modulus", "expected one of Pa, kPa, MPa, GPa"),  # was a TypeError (found by the flexure fuzz test)
    ("length: mm, modulus", "length: [mm], modulus", "units.length", "expected one of m, cm, mm"),
    ("{name: rod1,", "{name: [rod1],", "elements[0].name", "expected an element name (a string), got a list of 1 item"),
    ("bodies: [base, stage], frame: leg1", "bodies: [base, 7], frame: leg1", "elements[0].bodies[1]", "expected a body name (a string), got the number 7; write it in quotes"),
    ("{name: t1,", "{name: true,", "actuators[0].name", "expected an actuator name (a string), got true"),
    ("type: rod, bodies: [base, stage], frame: leg1", "type: [rod], bodies: [base, stage], frame: leg1", "elements[0].type", "unknown flexure element type ['rod']"),
    ("length: l, radius: r, material: aluminium}", "length: abc, radius: r, material: aluminium}", "elements[0].length", "unknown name 'abc'"),  # its key was written twice
    ("ground: base", "ground: 3", "ground", "expected a body name (a string), got the number 3"),
])
def test_names_and_units_of_the_wrong_kind_are_one_line_errors(tmp_path, old, new, key, words):
    text = FILE.read_text()
    assert old in text
    path = tmp_path / "bad.yaml"
    path.write_text(text.replace(old, new, 1))
    with pytest.raises(MechanismFileError) as info:
        load_flexure(path)
    message = str(info.value)
    assert message.startswith(f"{path}:") and f": {key}: " in message and words in message and "\n" not in message
