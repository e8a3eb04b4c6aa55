"""The YAML writer: what it writes reads back to the same joints, at every scale."""

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

import mobility
from mobility.io.writer import mechanism_to_yaml
from conftest import MECHANISMS

from builders import transformed  # noqa: E402  (tests/ is on the path)
from mobility.core.transforms import Transform

LIBRARY = sorted(MECHANISMS.glob("*.yaml"))


def same_joints(a: mobility.Mechanism, b: mobility.Mechanism, size: float = 0.0) -> bool:
    """Same joints; numbers equal to the bit (``size`` 0) or to the round-off of lengths ``size`` and directions 1."""
    for x, y in zip(a.world_joints, b.world_joints, strict=True):
        if (x.name, x.type, x.links, x.actuated) != (y.name, y.type, y.links, y.actuated):
            return False
        for field, scale in (("axis", 1.0), ("normal", 1.0), ("point", size), ("pitch", size)):
            u, v = getattr(x, field), getattr(y, field)
            if (u is None) != (v is None):
                return False
            if u is not None and not np.allclose(np.asarray(u), np.asarray(v), rtol=0.0, atol=1e-12 * (scale if size else 0.0)):
                return False
    return True


@settings(max_examples=40, deadline=None)
@given(st.sampled_from(LIBRARY), st.integers(-300, 300))
def test_written_files_read_back_to_the_same_joints_at_any_scale(path, exponent):
    m = transformed(mobility.load(path), Transform.identity(), 10.0**exponent)
    back = mobility.loads(mechanism_to_yaml(m))
    size = float(np.sqrt(np.mean([np.sum(np.square(np.asarray(j.point) / 10.0**exponent)) for j in m.world_joints if j.point is not None]))) * 10.0**exponent
    assert same_joints(m, back, 10.0 * size or 10.0**exponent)  # equal up to round-off, which is written as 0 (every point at the origin: the scale's)
    assert same_joints(back, mobility.loads(mechanism_to_yaml(back)))  # and then to the bit
    r, s = mobility.analyze(m), mobility.analyze(back)
    assert (r.dof, r.pattern, r.mobility) == (s.dof, s.pattern, s.mobility)


def test_round_off_is_written_as_zero_relative_to_the_mechanism():
    m = mobility.load(MECHANISMS / "four_bar.yaml")
    tiny = transformed(m, Transform.identity(), 1e-250)
    text = mechanism_to_yaml(tiny)
    assert "point: [1e-250, 2e-250, 0]" in text  # not rounded to zero: the whole mechanism is that small
    assert mobility.analyze(mobility.loads(text)).pattern == "1R"


def test_the_last_digits_of_round_off_are_not_written():
    z = (0.0, 0.0, 1.0)
    m = mobility.Mechanism("sums", "g", "b", (
        mobility.Joint("A", "R", ("g", "a"), axis=z, point=(0.0, 0.1, 0.1 + 0.05)),   # 0.15000000000000002
        mobility.Joint("B", "R", ("a", "b"), axis=z, point=(0.1 + 0.2, 1.0 - 0.9, 0.1)),  # 0.30000000000000004, 0.09999999999999998
        mobility.Joint("C", "H", ("b", "c"), axis=z, point=(1.0 / 3.0, 0.0, 0.0), pitch=0.7 + 0.1)))  # 0.7999999999999999
    text = mechanism_to_yaml(m)
    assert "point: [0, 0.1, 0.15]" in text and "point: [0.3, 0.1, 0.1]" in text and "pitch: 0.8" in text
    assert "point: [0.3333333333333333, 0, 0]" in text  # a number without round-off keeps its digits
    back = mobility.loads(text)
    assert same_joints(m, back, 10.0)  # equal up to round-off
    assert mechanism_to_yaml(back) == text  # idempotent: what was read is written as the same text
    assert same_joints(back, mobility.loads(mechanism_to_yaml(back)))  # and the second round trip to the bit


@settings(max_examples=300, deadline=None)
@given(st.integers(-10**7, 10**7), st.integers(-10**7, 10**7))
def test_a_sum_of_lengths_is_written_as_its_decimal_and_read_back_to_the_same_text(ia, ib):
    # lengths written to the millimetre, in metres, added up as a robot file's body positions are: the sum's noise is not written
    from fractions import Fraction

    from mobility.io.writer import _number

    a, b = ia / 1000, ib / 1000
    size = max(abs(a), abs(b), 1e-3)  # the mechanism is as large as its numbers
    text = _number(a + b, size)
    assert float(text) == float(Fraction(ia + ib, 1000))  # the decimal that was meant, not 0.15000000000000002
    assert _number(float(text), size) == text  # written again as the same text
