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
    assert same_joints(m, back, 10.0 * size)  # equal up to round-off, which is written as 0
    assert same_joints(back, mobility.loads(mechanism_to_yaml(back)))  # and then to the bit
    r, s = mobility.analyze(m), mobility.analyze(back)
    assert (r.dof, r.pattern, r.mobility) == (s.dof, s.pattern, s.mobility)


def test_round_off_is_written_as_zero_relative_to_the_mechanism():
    m = mobility.load(MECHANISMS / "four_bar.yaml")
    tiny = transformed(m, Transform.identity(), 1e-250)
    text = mechanism_to_yaml(tiny)
    assert "point: [1e-250, 2e-250, 0]" in text  # not rounded to zero: the whole mechanism is that small
    assert mobility.analyze(mobility.loads(text)).pattern == "1R"
