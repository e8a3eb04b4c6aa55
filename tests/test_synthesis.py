"""Type synthesis of limbs for the 2T3R pattern (Table 1 of Sun et al. 2018) and assembled PKMs.

The enumeration runs once per module (about 8 s on an idle 2-core machine: 5-joint limbs, every
candidate, both routes; see the module docstring of mobility.synthesis.enumeration);
every check compares its answer with a second route: least-squares fits of
sampled finite motions, the analyzer, or an independent explanation of why a
limb qualifies.
"""

import json
import math
import re
import warnings

import numpy as np
import pytest

import mobility
from mobility.core.finite_screws import Limb, ScrewJoint
from mobility.core.screws import same_subspace
from mobility.core.tolerance import Tolerance
from mobility.cli import main
from mobility.core.transforms import Transform, rotation_from_rpy
from mobility.errors import RequestError, SynthesisError
from mobility.io.writer import mechanism_to_yaml
from mobility.report.synthesis import synthesis_json, synthesis_text, written_files_text
from mobility.synthesis import (
    TABLE_1_2T3R,
    CandidateJoint,
    PatternFactor,
    assemble_pkm,
    generates,
    named_pattern,
    pkm_document,
    synthesize,
    write_pkm_files,
)
from mobility.synthesis.generic_rank import chain_twists, generic_rank
from mobility.synthesis.limb_types import joint_groups, limb_types

from conftest import MECHANISMS

MACHINE = dict(directions=((0, 0, 1), (0, 1, 0)))  # s1 vertical: the leg of a machine


@pytest.fixture(scope="module")
def result():
    return synthesize(named_pattern("2T3R", **MACHINE), seed=0, verify_samples=1)


def names(res):
    return {s.name for s in res.structures}


def test_table_1_is_reproduced(result):
    assert set(TABLE_1_2T3R) <= names(result)
    for s in result.structures:
        assert s.in_table_1 == (s.name in TABLE_1_2T3R)
    assert result.verified_samples == result.sequences  # every kept sequence passed the sample route


def test_table_1_direction_conditions(result):
    """Rc axes along s1 x s2, P in the plane of s1 and s2, S and U centred at O (the paper's conditions)."""
    c = np.cross(result.directions["s1"], result.directions["s2"])
    plane = np.array([result.directions["s1"], result.directions["s2"]])
    for name in TABLE_1_2T3R:
        for seq in result.structure(name).realizations:
            for cand in seq:
                axis = np.array(cand.joint.axis)
                if cand.joint.kind == "P":
                    assert abs(axis @ c) < 1e-12
                    assert np.linalg.matrix_rank(np.vstack([plane, axis]), tol=1e-9) == 2
                elif cand.point != "O":  # an R off O: an Rc
                    assert np.allclose(np.abs(axis), np.abs(c))
    for name in ("SP1P2", "SRcRc", "SP1Rc", "SRcP1"):
        assert result.structure(name).groups[0] == "S"
    for name in ("UP1P2Rc", "UP1RcP2", "UP1RcRc"):
        assert result.structure(name).groups[0] == "U"


def test_every_limb_found_fits_the_pattern_by_least_squares(result):
    """Second route, with fresh random motions (seed differs from the synthesis)."""
    pattern = result.pattern
    rng = np.random.default_rng(12345)
    for s in result.structures:
        limb = Limb(tuple(c.joint for c in s.realizations[-1]))
        q = rng.uniform(-math.pi, math.pi, len(limb))
        q[[j.kind == "P" for j in limb.joints]] *= pattern.length / math.pi
        _, residual = pattern.fit(limb.transform(q), seed=1)
        assert residual < 1e-9, s.name


def test_rank_route_agrees_with_sample_route_on_random_chains(result):
    """Random 5-joint chains from the candidates: the rank route's verdict against sampled fits and dimension."""
    rng = np.random.default_rng(7)
    pattern = result.pattern
    alphabet = [c.joint for c in result.alphabet]
    verdicts = []
    for _ in range(16):
        chain = [alphabet[k] for k in rng.integers(len(alphabet), size=5)]
        rank_says = generates(pattern, chain, seed=3)
        limb = Limb(tuple(chain))
        motions = [limb.transform(rng.uniform(-2.5, 2.5, 5)) for _ in range(2)]
        inside = all(pattern.contains(m, seed=2) for m in motions)
        full = np.linalg.matrix_rank(limb.twists(rng.uniform(-2.5, 2.5, 5)), tol=1e-8) == 5
        assert rank_says == (inside and full)
        verdicts.append(rank_says)
    assert not all(verdicts)  # the sample contains chains that fail


def test_translations_before_the_rotations_are_rejected(result):
    """P1P2S (rotations about a point carried by the slides) is another 2T3R set, not this pattern."""
    assert not any(n.startswith("P") for n in names(result))
    pattern = result.pattern
    s, s1, s2 = ([ScrewJoint("R", e) for e in np.eye(3)], ScrewJoint("P", (0, 0, 1)), ScrewJoint("P", (0, 1, 0)))
    limb = Limb((s1, s2, *s))
    assert not generates(pattern, limb.joints)
    assert not pattern.contains(limb.transform([100.0, -50.0, 0.4, -0.3, 0.2]))
    assert {c.label for c in result.rejected_joints} >= {"P[c]"}


def _explained(seq, groups):
    """Why a limb outside Table 1 still has the 2T3R motion, from its joints alone.

    (a) a U directly followed by an Rc: Rot(c through g) = Rot(c through O) then a translation in
        the plane, so the three rotations are those of an S at O followed by the plane motion;
    (b) a P next to an R through O along the P's own direction: they commute, so the R joins the
        rotations about O and the P the translations.
    """
    if any(a == "U" and b == "Rc" for a, b in zip(groups, groups[1:])):
        return True
    for a, b in zip(seq, seq[1:]):
        pair = {a.joint.kind, b.joint.kind}
        if pair == {"P", "R"} and a.direction == b.direction and "O" in (a.point, b.point):
            return True
    return False


def test_further_limbs_are_explained(result):
    extras = [s for s in result.structures if not s.in_table_1]
    assert extras, "the enumeration finds more than Table 1"
    for s in extras:
        assert any(_explained(seq, s.groups) for seq in s.realizations), s.name
    assert {"URcP1P2", "URcP1Rc", "URcRcP1", "URcRcRc"} <= names(result)


def test_synthesis_does_not_depend_on_placement_or_on_the_plane_basis():
    """3-joint limbs of 2T3R: same types for a moved O and a non-orthogonal s1, s2."""
    a = synthesize(named_pattern("2T3R"), joints=3, verify_samples=1)
    b = synthesize(named_pattern("2T3R", point=(3.0, -2.0, 7.0), directions=((1, 1, 0.5), (-0.2, 1, 1))), joints=3, verify_samples=1, seed=5)
    assert names(a) == names(b)
    assert "S" in names(a) and "UP1" in names(a) and "P1P2S" not in names(a)


def test_other_patterns():
    """3T: every 3-joint limb of P joints along independent directions; 3R: three R through O."""
    three_t = synthesize("3T", verify_samples=1)
    assert names(three_t) == {"P1P2P3"}
    three_r = synthesize("3R", verify_samples=1)
    assert names(three_r) == {"S"}
    planar = synthesize("2T1R", verify_samples=1)
    assert {"P1P2Ra1", "Ra1Ra1Ra1", "P1Ra1P2"} <= names(planar)


def test_pattern_errors():
    with pytest.raises(SynthesisError):
        named_pattern("7T")
    with pytest.raises(SynthesisError):
        synthesize("2T3R", joints=0)


# -- assembly ------------------------------------------------------------------------------


@pytest.mark.parametrize("name", TABLE_1_2T3R)
def test_assembled_pkms_have_5_dof_2t3r(result, name):
    m = assemble_pkm(result, name)
    r = mobility.analyze(m)
    assert (r.dof, r.pattern, r.idle_dof) == (5, "2T3R", 0)
    # the constraint: a force through O along s1 x s2
    c = np.cross(result.directions["s1"], result.directions["s2"])
    assert same_subspace(r.wrenches.T, np.concatenate([c, np.zeros(3)])[:, None])
    text = mechanism_to_yaml(m)
    back = mobility.loads(text)
    assert [j.name for j in back.joints] == [j.name for j in m.joints]
    assert all(np.allclose(a.point or 0, b.point or 0) and a.actuated == b.actuated for a, b in zip(back.joints, m.joints))


def test_metrom_is_spr_4sprr(result):
    m = assemble_pkm(result, "SP1Rc", other="SPRR")
    assert [j.type for j in m.joints[:3]] == ["S", "P", "R"]
    assert mobility.analyze(m).pattern == "2T3R"


def test_a_limb_singular_at_home_is_not_assembled(result):
    with pytest.raises(SynthesisError):
        assemble_pkm(result, "UP1U")


def test_pkm_document_expected_block(result):
    m, text = pkm_document(result, "UP1RcRc")
    assert "expected: {dof: 5, pattern: 2T3R, mobility: 5}" in text
    assert mobility.loads(text).expected.dof == 5


@pytest.mark.parametrize("path", sorted(MECHANISMS.glob("pkm_*.yaml")) + [MECHANISMS / "metrom.yaml"], ids=lambda p: p.name)
def test_mechanism_files(path):
    m = mobility.load(path)
    r = mobility.analyze(m)
    assert (r.dof, r.pattern, r.mobility) == (m.expected.dof, m.expected.pattern, m.expected.mobility) == (5, "2T3R", 5)
    # moved rigidly: same answer (tolerance policy)
    moved = mobility.analyze(
        m.replace(joints=tuple(j.transformed(Transform(rotation_from_rpy((0.3, -0.2, 1.0)), np.array([5.0, -7.0, 2.0]))) for j in m.world_joints))
    )
    assert (moved.dof, moved.pattern) == (5, "2T3R")


# -- the pieces of the synthesis, each against a second route --------------------------------


@pytest.mark.parametrize("seed", range(3))
def test_batch_chain_twists_are_the_limbs_derivatives(seed):
    """chain_twists (many poses at once, by carried axes) equals Limb.twists (derivative of the finite screw)."""
    rng = np.random.default_rng(seed)
    joints = tuple(ScrewJoint(k, rng.normal(size=3), rng.normal(size=3), pitch=0.4) for k in "RPHRRP")
    q = rng.uniform(-3, 3, (4, len(joints)))
    batch = chain_twists(joints, q)
    for k in range(len(q)):
        assert np.allclose(batch[k], Limb(joints).twists(q[k]), atol=1e-9)


def test_generic_rank_counts_the_dimension_of_the_motion():
    rng = np.random.default_rng(0)
    spherical = [ScrewJoint("R", e) for e in np.eye(3)]
    # three R through a point: 3; two parallel R axes and a P normal to them: 3 (planar); P twice along x: 1
    planar = [ScrewJoint("R", (0, 0, 1)), ScrewJoint("R", (0, 0, 1), (1, 0, 0)), ScrewJoint("P", (1, 0, 0))]
    assert generic_rank(spherical, rng, 3, 1.0) == 3
    assert generic_rank(planar, rng, 3, 1.0) == 3
    assert generic_rank([ScrewJoint("P", (1, 0, 0))] * 2, rng, 3, 1.0) == 1
    # the same chain scaled by 1000 (lengths over L = 1000): the same rank
    big = [ScrewJoint("R", (0, 0, 1)), ScrewJoint("R", (0, 0, 1), (1000, 0, 0)), ScrewJoint("P", (1, 0, 0))]
    assert generic_rank(big, rng, 3, 1000.0) == 3


def test_membership_is_decided_by_the_closure_tolerance():
    """A motion of the pattern moved off it by 1e-9 of its length along c is out; with a looser closure it is in."""
    pattern = named_pattern("2T3R", point=(0, 0, 0), directions=((0, 0, 1), (0, 1, 0)))
    motion = pattern.transform(np.array([0.2, -0.1, 0.3, 1.5, -0.7]))
    assert pattern.contains(motion)
    off = motion.copy()
    off[0, 3] += 1e-9 * pattern.length  # along c = s1 x s2 = -x: no motion of the pattern reaches it
    assert not pattern.contains(off)
    assert pattern.contains(off, tol=Tolerance(closure=1e-6))
    _, residual = pattern.fit(off)
    assert 0.5e-9 < residual < 2e-9  # the fit's residual is the offset, in units of the pattern's length


def test_pattern_factors_and_points():
    f = PatternFactor("translations", directions=((2, 0, 0), (0, 3, 0)))
    assert f.dim == 2 and f.directions == ((1.0, 0.0, 0.0), (0.0, 1.0, 0.0))
    assert np.allclose(f.transform(np.array([1.0, 2.0]))[:3, 3], [1, 2, 0])
    with pytest.raises(SynthesisError):
        PatternFactor("translations", directions=((1, 0, 0), (2, 0, 0)))  # dependent
    with pytest.raises(SynthesisError):
        PatternFactor("spin")
    with pytest.raises(SynthesisError):
        PatternFactor("rotation", (0, 0, 0), ((0, 0, 0),))  # a zero direction
    # a point given by two factors is one point of the pattern; the direction set completes space
    schoenflies = named_pattern("3T1R", point=(1, 2, 3))
    assert schoenflies.points == ((1.0, 2.0, 3.0),)
    assert [label for label, _ in named_pattern("3R").directions()] == ["x", "y", "z"]
    with pytest.raises(SynthesisError):
        named_pattern("3T1R", directions=((1, 0, 0),))
    with pytest.raises(SynthesisError):
        named_pattern("2T3R", point=(1, 2))


def test_request_errors():
    with pytest.raises(SynthesisError):
        synthesize("3R", samples=0)
    with pytest.raises(SynthesisError):
        synthesize("3R", verify_samples=-1)
    with pytest.raises(SynthesisError):
        generates(named_pattern("3R"), [ScrewJoint("R", (0, 0, 1))], samples=0)
    res = synthesize("3R", verify_samples=0)
    with pytest.raises(SynthesisError, match="found: S"):
        res.structure("SS")
    with pytest.raises(SynthesisError):
        assemble_pkm(res, "S", other="RRR")


def test_limb_types_group_and_name_joint_sequences():
    """The names of the groups, against the sequences written by hand."""
    R = lambda d, e, p="O": CandidateJoint(ScrewJoint("R", e), d, p)  # noqa: E731
    P = lambda d, e: CandidateJoint(ScrewJoint("P", e), d)  # noqa: E731
    x, y, z = np.eye(3)
    s = (R("s1", x), R("s2", y), R("c", z))
    seqs = [s + (P("s1", x), P("s2", y)), s + (P("s2", y), P("s1", x)), (R("s1", x), R("c", z), P("s1", x), R("c", z, "g1"), R("c", z, "g2"))]
    types = limb_types(seqs, "2T3R", ("s1", "s2"))
    assert [t.name for t in types] == ["SP1P2", "UP1RcRc"]
    assert [len(t.realizations) for t in types] == [2, 1]
    assert types[0].in_table_1 and types[1].in_table_1
    assert types[0].conditions == ("S: three R through O", "P1: along s1 or s2", "P2: along s1 or s2")
    assert types[1].to_dict()["realizations"] == [["R[s1@O]", "R[c@O]", "P[s1]", "R[c@g1]", "R[c@g2]"]]
    assert [g for g, _ in joint_groups((P("c", z),), ("s1", "s2"))] == ["Pc"]


def test_write_pkm_files(tmp_path):
    res = synthesize("3R", verify_samples=0)
    written, skipped = write_pkm_files(res, tmp_path / "new", other="SPRR")
    assert skipped == () and [p.split("/")[-1] for p in written] == ["pkm_s_4sprr.yaml"]
    back = mobility.load(written[0])
    r = mobility.analyze(back)
    assert (r.dof, r.pattern) == (back.expected.dof, back.expected.pattern) == (3, "3R")
    blocker = tmp_path / "file"
    blocker.write_text("")
    with pytest.raises(RequestError):
        write_pkm_files(res, blocker / "sub")


def test_synthesis_reports():
    res = synthesize("3R", verify_samples=1)
    text = synthesis_text(res)
    assert text.splitlines()[0] == "3R: rotations about the fixed point O"
    assert "limb types of 3 one-DOF joints whose finite motions are the pattern: 1 (12 joint sequences)" in text
    assert "    S  " in text and "S: three R through O" in text
    data = json.loads(synthesis_json(res, ["a.yaml"], ["X: singular"]))
    assert data["written"] == ["a.yaml"] and data["skipped"] == ["X: singular"] and data["structures"][0]["name"] == "S"
    assert written_files_text("d", ["d/a.yaml"], ["X: why"]).splitlines() == [
        "wrote 1 mechanism files to d; not assembled (singular at the home pose): 1",
        "  X: why",
    ]


@pytest.mark.parametrize("name", ["3R", "3T1R", "2T3R"])
def test_the_limbs_found_do_not_depend_on_where_the_pattern_is(name):
    home = synthesize(named_pattern(name), verify_samples=1)
    for point in ((7.0, -3.0, 2.0), (1e200, 0.0, 0.0)):
        moved = synthesize(named_pattern(name, point=point), verify_samples=1)
        assert moved.pattern.dim == home.pattern.dim
        assert [s.name for s in moved.structures] == [s.name for s in home.structures]
        assert moved.points["O"] == point


@pytest.mark.parametrize("name, directions, message", [
    ("3T", [(1, 0, 0)], "the 3T pattern takes 3 directions, got 1"),
    ("3T", [(1, 0, 0), (0, 1, 0), (0, 0, 1), (1, 1, 1)], "the 3T pattern takes 3 directions, got 4"),
    ("3R", [(1, 0, 0)], "the 3R pattern takes no directions, got 1"),
    ("2T1R", [(1, 0, 0), (2, 0, 0)], "the directions of the 2T1R pattern must be independent"),
    ("3T", [(0, 0, 0), (0, 1, 0), (0, 0, 1)], "expected a non-zero finite direction"),
])
def test_directions_that_do_not_fit_the_pattern_are_refused(name, directions, message):
    with pytest.raises(SynthesisError, match=re.escape(message)):
        named_pattern(name, directions=directions)


def test_extreme_directions_are_normalised_without_overflow():
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        big = named_pattern("3T", directions=[(1e308, 1e308, 0), (0, 1, 0), (0, 0, 1)])
        tiny = named_pattern("3T", directions=[(1e-320, 0, 0), (0, 1, 0), (0, 0, 1)])
    assert np.allclose(big.translation_directions[0], (2**-0.5, 2**-0.5, 0)) and np.allclose(tiny.translation_directions[0], (1, 0, 0))


def test_fewer_joints_than_the_pattern_are_parts_of_limbs_and_more_are_refused(capsys):
    assert main(["synthesize", "3R", "--joints", "1"]) == 0
    out = capsys.readouterr().out
    assert "chains of 1 one-DOF joints whose finite motions lie in the pattern (fewer joints than its dimension 3: parts of limbs, not limbs): 3" in out
    assert "whose finite motions are the pattern" not in out  # they are not: one joint moves in one dimension of three
    assert main(["synthesize", "3T", "--joints", "4"]) == 2
    assert "a chain of 4 independent one-DOF joints has 4 freedoms, more than the 3 of 3T" in capsys.readouterr().err
    with pytest.raises(SynthesisError, match="more than the 5 of 2T3R"):
        synthesize(named_pattern("2T3R"), joints=6)


def test_write_refuses_before_the_search_and_never_overwrites(tmp_path, capsys):
    (tmp_path / "afile").write_text("x")
    for folder, said in ((tmp_path / "afile", "is a file, expected a folder"), (tmp_path / "no" / "sub", "does not exist")):
        assert main(["synthesize", "3T", "--write", str(folder)]) == 2
        assert said in capsys.readouterr().err
    assert main(["synthesize", "3R", "--joints", "2", "--write", str(tmp_path / "parts")]) == 2
    assert "--write assembles PKMs from limbs of 3 joints" in capsys.readouterr().err and not (tmp_path / "parts").exists()
    out = tmp_path / "out"
    assert main(["synthesize", "3T", "--write", str(out)]) == 0
    (written,) = out.iterdir()
    written.write_text("# annotated by hand\n")
    assert main(["synthesize", "3T", "--write", str(out)]) == 2
    assert f"--write {out}: would overwrite {written}" in capsys.readouterr().err
    assert written.read_text() == "# annotated by hand\n"
