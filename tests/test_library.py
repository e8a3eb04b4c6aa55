"""The bundled library of classic mechanisms (mechanisms/*.yaml).

Every file is cross-checked by the independent loop-closure route; the files that
claim a literature condition (Bennett, Goldberg, Myard, Bricard) are checked to
satisfy it from their joint lines alone; breaking the condition must make the loop
rigid; the special answers of the issue (3-PRS pure rotations and their coupling
away from the symmetric pose, Xie's 2R1T limbs, G-K failures, idle spins) are
asserted one by one.
"""

import math
import re

import numpy as np
import pytest
from builders import transformed
from conftest import MECHANISMS

import mobility
from mobility.core.loop_closure import loop_closure
from mobility.core.screws import free_vector_subspace, same_subspace
from mobility.core.transforms import Transform

LIBRARY = (
    "3crr", "3prs", "3prs_tilted", "3rps", "3upu_singular", "4puu", "4puu_singular", "6sps", "6ups",
    "agile_eye", "bennett", "bricard_line_symmetric", "delta", "four_bar", "goldberg_5r", "h4",
    "hooke_joint", "myard_5r", "orthoglide", "parallelogram", "planar_3rrr", "planar_5r", "rssr",
    "sarrus", "scara", "slider_crank", "stephenson_six_bar", "tricept", "tsai_3upu", "xie_2r1t",
    "xy_sprint_hybrid", "schatz", "bricard_orthogonal", "bricard_plane_symmetric", "bricard_trihedral",
    "spatial_7r_generic", "tripteron_3prrr", "exechon", "3ruu", "hexa_6rus", "planar_3rpr", "spherical_3rrr",
    "3upu_wrist", "4ruu_schoenflies", "four_bar_change_point", "wrist_gimbal_lock",
)
"""The files of the classic-mechanism library (other helpers add more files to the folder)."""

ALL_FILES = sorted(MECHANISMS.glob("*.yaml"))
FREEDOMS = {"R": 1, "P": 1, "H": 1, "C": 2, "U": 2, "S": 3, "E": 3}


def load(stem: str) -> mobility.Mechanism:
    return mobility.load(MECHANISMS / f"{stem}.yaml")


def analyze_text(text: str) -> mobility.Result:
    return mobility.analyze(mobility.loads(text))


def test_the_library_has_what_the_issues_ask_for():
    names = {p.stem for p in ALL_FILES}
    assert set(LIBRARY) <= names
    assert len(LIBRARY) >= 25


@pytest.mark.parametrize("stem", LIBRARY)
def test_file_cites_its_source_and_the_gk_count(stem):
    m = load(stem)
    assert m.expected is not None
    keys = dict(m.expected.items())
    assert {"dof", "pattern", "mobility"} <= set(keys)
    assert re.search(r"\b(18|19|20)\d\d\b", m.description), "a source with its year"
    assert "Grübler" in m.description
    # the count written in the description is the count of the joint graph
    joints = m.joints
    gk = 6 * (len(m.links) - 1 - len(joints)) + sum(FREEDOMS[j.type] for j in joints)
    assert keys.get("gruebler_kutzbach", gk) == gk
    assert str(gk) in m.description.replace("−", "-")


@pytest.mark.parametrize("path", ALL_FILES, ids=[p.stem for p in ALL_FILES])
def test_loop_closure_route_agrees(path):
    """The screw route and the loop-closure route find the same mobility, DOF and translations."""
    m = mobility.load(path)
    r = mobility.analyze(m)
    lc = loop_closure(m)
    assert lc.mobility == r.mobility
    assert lc.end_effector_twists.shape[1] == r.dof
    free, _, _ = free_vector_subspace(lc.end_effector_twists)
    assert free.shape[1] == r.translations.shape[0]
    if free.shape[1]:
        assert same_subspace(free, r.translations.T)
    assert same_subspace(lc.world_twists.T, r.twists.T) or r.dof == 0  # the whole twist systems, in the file's frame and unit


# --- the paradox linkages satisfy their conditions, from the joint lines alone -------------


def common_normal(p1, d1, p2, d2):
    """Length, twist (sine) and the feet on each line of the common normal of two skew lines."""
    d1, d2 = np.asarray(d1) / np.linalg.norm(d1), np.asarray(d2) / np.linalg.norm(d2)
    n = np.cross(d1, d2)
    s = np.linalg.norm(n)
    a = np.array([d1, -d2, n]).T
    t1, t2, _ = np.linalg.solve(a, np.asarray(p2) - np.asarray(p1))
    f1, f2 = np.asarray(p1) + t1 * d1, np.asarray(p2) + t2 * d2
    return np.linalg.norm(f2 - f1), s, f1, f2


def loop_parameters(m, order):
    """Link lengths, twist sines and joint offsets around the loop of joints ``order``."""
    lines = {j.name: (np.array(j.point), np.array(j.axis)) for j in m.world_joints}
    k = len(order)
    links = [common_normal(*lines[order[i]], *lines[order[(i + 1) % k]]) for i in range(k)]
    offsets = [np.linalg.norm(links[i][2] - links[i - 1][3]) for i in range(k)]
    return [x[0] for x in links], [x[1] for x in links], offsets


def test_bennett_conditions_hold_to_machine_precision():
    a, s, d = loop_parameters(load("bennett"), ["J1", "J2", "J3", "J4"])
    scale = max(a)
    assert abs(a[0] - a[2]) < 1e-12 * scale and abs(a[1] - a[3]) < 1e-12 * scale
    assert abs(s[0] - s[2]) < 1e-12 and abs(s[1] - s[3]) < 1e-12
    assert abs(a[0] / s[0] - a[1] / s[1]) < 1e-12 * scale  # a / sin(alpha) = b / sin(beta)
    assert max(d) < 1e-10 * scale  # no offsets


def test_goldberg_links_come_from_two_bennetts():
    m = load("goldberg_5r")
    a, s, d = loop_parameters(m, ["J2", "J3", "J4", "K3", "K2"])
    scale = max(a)
    # links J2-J3 and K3-K2 are the two copies of the shared Bennett link (b, beta)
    assert abs(a[0] - a[3]) < 1e-12 * scale and abs(s[0] - s[3]) < 1e-12
    ratios = [a[i] / s[i] for i in range(4)]  # b, a, c, b over their twist sines
    assert np.ptp(ratios) < 1e-11 * scale
    # the fused link has the collinear common normals: length a + c
    assert abs(a[4] - (a[1] + a[2])) < 1e-11 * scale


def test_myard_is_plane_symmetric():
    m = load("myard_5r")
    lines = {j.name: (np.array(j.point), np.array(j.axis)) for j in m.world_joints}
    mirror = np.diag([1.0, 1.0, -1.0])
    for left, right in (("J2", "K2"), ("J3", "K3"), ("J4", "J4")):
        (p, u), (q, v) = lines[left], lines[right]
        assert np.allclose(mirror @ p, q, atol=1e-12 * 100) and abs(abs((mirror @ u) @ v) - 1) < 1e-14
    a, s, _ = loop_parameters(m, ["J2", "J3", "J4", "K3", "K2"])
    assert abs(s[0] - 1) < 1e-14 and abs(a[1] - a[0] * s[1]) < 1e-12 * a[0]  # beta = 90 deg, a = b sin(alpha)


def test_bricard_is_line_symmetric():
    lines = {j.name: (np.array(j.point), np.array(j.axis)) for j in load("bricard_line_symmetric").world_joints}
    half_turn = np.diag([-1.0, -1.0, 1.0])
    for i in (1, 2, 3):
        (p, u), (q, v) = lines[f"J{i}"], lines[f"J{i + 3}"]
        assert np.array_equal(half_turn @ p, q) and np.allclose(half_turn @ u, v, atol=1e-15)


SIX = ["J1", "J2", "J3", "J4", "J5", "J6"]


@pytest.mark.parametrize("stem", ["bricard_trihedral", "bricard_orthogonal", "schatz"])
def test_trihedral_bricards_satisfy_their_conditions(stem):
    # consecutive axes at right angles, no offsets, and a12^2 + a34^2 + a56^2 = a23^2 + a45^2 + a61^2
    a, s, d = loop_parameters(load(stem), SIX)
    scale = max(a)
    assert max(abs(x - 1.0) for x in s) < 1e-12 and max(d) < 1e-10 * scale
    assert abs(a[0] ** 2 + a[2] ** 2 + a[4] ** 2 - a[1] ** 2 - a[3] ** 2 - a[5] ** 2) < 1e-10 * scale**2
    if stem == "bricard_orthogonal":
        assert np.ptp(a) < 1e-10 * scale
    if stem == "schatz":  # a12 = a34 = 0, a23 = a45 = a61, a56 the diagonal of the cube they span
        assert a[0] < 1e-10 * scale and a[2] < 1e-10 * scale and np.ptp([a[1], a[3], a[5]]) < 1e-10 * scale
        assert abs(a[4] - math.sqrt(3) * a[1]) < 1e-10 * scale


def test_plane_symmetric_bricard_satisfies_its_conditions():
    a, s, d = loop_parameters(load("bricard_plane_symmetric"), SIX)
    scale = max(a)
    for i, j in ((0, 5), (1, 4), (2, 3)):  # a12 = a61, a23 = a56, a34 = a45 and their twists alpha + alpha' = 360 deg
        assert abs(a[i] - a[j]) < 1e-10 * scale and abs(s[i] - s[j]) < 1e-12
    assert d[0] < 1e-10 * scale and d[3] < 1e-10 * scale  # R1 = R4 = 0
    assert abs(d[1] - d[5]) < 1e-10 * scale and abs(d[2] - d[4]) < 1e-10 * scale  # R2 = -R6, R3 = -R5
    assert min(d[1], d[2]) > 1e-3 * scale  # a general one: the offsets are not all zero


@pytest.mark.parametrize("stem", ["bricard_trihedral", "bricard_plane_symmetric", "bricard_orthogonal", "schatz"])
def test_the_bricards_move_through_a_full_cycle(stem):
    # Grübler–Kutzbach says 0; the screw route says 1 at the pose; moving the loop shows the freedom is finite
    fm = mobility.finite_mobility(load(stem))
    assert (fm.verdict, fm.full_cycle_mobility, fm.full_cycle_dof) == ("full-cycle", 1, 1)


def test_the_change_point_four_bar_is_a_bifurcation_of_two_one_dof_branches():
    # kept out of the file's expected block (mobility check stays within its time budget); the same verdict
    # as the parallelogram's change point, with no two links equal
    fm = mobility.finite_mobility(load("four_bar_change_point"))
    assert (fm.verdict, fm.instantaneous_mobility, fm.full_cycle_mobility, fm.full_cycle_dof) == ("bifurcation", 2, 1, 1)
    assert len(fm.branches) == 2 and all(b.dof == 1 and b.pattern == "1R" for b in fm.branches)


@pytest.mark.parametrize(
    "stem, old, new",
    [
        ("bennett", 'b: "a * sind(beta) / sind(alpha)"', 'b: "1.001 * a * sind(beta) / sind(alpha)"'),
        ("goldberg_5r", 'c: "b * sind(gamma) / sind(beta)"', 'c: "1.001 * b * sind(gamma) / sind(beta)"'),
        ("myard_5r", 'a: "b * sind(alpha)"', 'a: "1.001 * b * sind(alpha)"'),
        ("bricard_line_symmetric", 'point: ["-p1x", "-p1y", p1z]', 'point: ["-1.001*p1x", "-p1y", p1z]'),
        ("sarrus", "axis: [0, 1, 0], point: [100, 0, \"h/2\"]", "axis: [0, 1, 0.05], point: [100, 0, \"h/2\"]"),
    ],
)
def test_breaking_the_condition_makes_the_loop_rigid(stem, old, new):
    text = (MECHANISMS / f"{stem}.yaml").read_text()
    assert old in text
    assert load(stem).expected.dof == 1 and analyze_text(text).dof == 1
    broken = analyze_text(text.replace(old, new))
    assert (broken.dof, broken.mobility) == (0, 0)


# --- the answers the issues single out --------------------------------------------------------


def test_3prs_symmetric_pose_has_pure_rotations_in_the_plane_of_the_spheres():
    r = mobility.analyze(load("3prs"))
    assert r.pattern == "1T2R" and np.allclose(np.abs(r.translations), [[0, 0, 1]])
    assert len(r.rotations) == 2
    for axis in r.rotations:
        assert axis.pitch == 0.0 and axis.kind == "rotation"
        assert abs(axis.axis[2]) < 1e-12 and abs(axis.point[2]) < 1e-9  # in the plane z = 0 of the sphere centres


def test_3prs_tilted_pose_couples_rotation_with_translation():
    r = mobility.analyze(load("3prs_tilted"))
    assert r.pattern == "1T2R" and np.allclose(np.abs(r.translations), [[0, 0, 1]])
    pitches = [abs(a.pitch) for a in r.rotations]
    assert max(pitches) > 1e-3 * r.length_scale
    assert any(a.kind == "helical" for a in r.rotations)


def test_xie_2r1t_limbs_share_constraints_and_limb_3_is_free():
    r = mobility.analyze(load("xie_2r1t"))
    assert r.pattern == "1T2R" and all(a.pitch == 0.0 for a in r.rotations)
    limbs = {limb.structure.split("(")[1].split(",")[0]: limb for limb in r.limbs}
    one, two, three = limbs["P1"], limbs["P2"], limbs["U3"]
    assert one.wrenches.shape[0] == two.wrenches.shape[0] == 3
    assert same_subspace(one.wrenches.T, two.wrenches.T)
    assert three.dof == 6 and three.wrenches.shape[0] == 0
    assert r.redundant_constraints == 3


@pytest.mark.parametrize("stem", ["4puu", "3crr", "orthoglide", "xie_2r1t", "agile_eye", "planar_3rrr"])
def test_gruebler_kutzbach_is_wrong_for_overconstrained_machines(stem):
    r = mobility.analyze(load(stem))
    assert r.gruebler_kutzbach < r.mobility
    assert r.redundant_constraints == r.mobility - r.gruebler_kutzbach == load(stem).expected.redundant_constraints


@pytest.mark.parametrize("stem", ["delta", "h4", "rssr"])
def test_idle_dof_are_the_spins_of_the_ss_rods(stem):
    m = load(stem)
    spherical = {}
    for j in m.joints:
        if j.type == "S":
            for link in j.links:
                spherical[link] = spherical.get(link, 0) + 1
    rods = sum(1 for link, count in spherical.items() if count == 2 and all(j.type == "S" for j in m.joints if link in j.links))
    r = mobility.analyze(m)
    assert rods > 0 and r.idle_dof == rods
    assert r.mobility == r.dof + rods


def test_six_sps_legs_spin_where_six_ups_legs_do_not():
    ups, sps = mobility.analyze(load("6ups")), mobility.analyze(load("6sps"))
    assert (ups.dof, sps.dof, ups.pattern, sps.pattern) == (6, 6, "3T3R", "3T3R")
    assert (ups.idle_dof, sps.idle_dof) == (0, 6)
    assert sps.gruebler_kutzbach - ups.gruebler_kutzbach == 6


def test_constraint_singular_variants_gain_a_rotation():
    for regular, singular in (("tsai_3upu", "3upu_singular"), ("4puu", "4puu_singular")):
        a, b = mobility.analyze(load(regular)), mobility.analyze(load(singular))
        assert (a.pattern, b.pattern) == ("3T", "3T1R")
        assert b.redundant_constraints == a.redundant_constraints + 1
        assert b.margin.smallest_kept > 1e-3  # a clean rank drop, not a near-singular pose


def test_non_series_parallel_graph_is_solved_as_a_bridge():
    r = mobility.analyze(load("stephenson_six_bar"))
    assert r.structure.startswith("bridge(")
    assert (r.dof, r.mobility) == (1, 1)


P_LOOP = """
name: loop of four sliders in space
ground: g
end_effector: c
joints:
  - {name: P1, type: P, links: [g, a], axis: [1, 0, 0]}
  - {name: P2, type: P, links: [a, b], axis: [0, 1, 0]}
  - {name: P3, type: P, links: [b, c], axis: [0, 0, 1]}
  - {name: P4, type: P, links: [c, g], axis: [1, 1, 1]}
"""


@pytest.mark.parametrize("text, motion", [
    (P_LOOP, "three couples: every joint only translates"),  # was "every joint moves in one plane or about one point"
    ("four_bar", "every joint moves in one plane"),
    ("planar_3rrr", "every joint moves in one plane"),
    ("spherical_3rrr", "three forces through one point: every joint turns about it"),
    ("agile_eye", "three forces through one point: every joint turns about it"),
    ("bennett", None),  # three common wrenches, none of those kinds: the count alone
])
def test_the_explanation_names_the_common_motion_only_when_the_common_wrenches_show_it(text, motion):
    m = mobility.loads(text) if text.startswith("\n") else load(text)
    for scale in (1.0, 1000.0):  # the kinds are read in normalised coordinates: a scale changes nothing
        r = mobility.analyze(transformed(m, Transform.identity(), scale))
        said = r.gruebler_kutzbach_explanation
        assert r.common_constraints == 3 and f"{3 * r.loops} of them come from 3 wrenches reciprocal to every joint twist" in said
        assert (f"twist ({motion}):" in said) if motion else f"twist: {'the loop' if r.loops == 1 else 'each loop'} loses" in said
