"""Joint and tendon equalities of a compiled MuJoCo model as couplings of joint rates.

MuJoCo's ``<equality><joint joint1 joint2 polycoef>`` holds
``q1 - q1_0 = c0 + c1 d + c2 d^2 + c3 d^3 + c4 d^4`` with ``d = q2 - q2_0``
(``q_0`` at ``qpos0``): at ``qpos0`` the rates obey ``q1' - c1 q2' = 0``.  A
tendon equality holds the same of two fixed tendons' lengths ``sum coef_j q_j``:
``sum coef1_j q_j' - c1 sum coef2_k q_k' = 0``.  A nonlinear polynomial acts
through its slope ``c1`` (a note); an equality holding a joint still (fewer
than two joints) and a spatial tendon are :class:`~mobility.io.robot_tree.Unsupported`.
"""

from __future__ import annotations

from ..errors import clipped
from .mjcf_actuators import CompiledModel
from .robot_couplings import TreeCoupling
from .robot_tree import Unsupported, at_line

__all__ = ["equality_coupling", "add_coupling", "tendons_held"]


def equality_coupling(model: CompiledModel, k: int, tag: str, key: str, line: int | None, notes: list[str]) -> TreeCoupling | Unsupported:
    """Equality ``k`` on joints or fixed tendons as a coupling of joint rates at ``qpos0`` (its slope there: ``polycoef[1]``)."""
    m = model.m
    first, second = int(m.eq_obj1id[k]), int(m.eq_obj2id[k])
    poly = [float(x) for x in m.eq_data[k][:5]]
    kind_name = "mjOBJ_JOINT" if tag == "joint" else "mjOBJ_TENDON"
    shown = ", ".join(clipped(model.name(kind_name, o) or str(o)) for o in (first, second) if o >= 0)
    if tag == "joint":
        terms = {first: 1.0}
        if second >= 0 and poly[1] != 0.0:
            terms[second] = terms.get(second, 0.0) - poly[1]
    else:
        terms = {}
        for tendon, sign in ((first, 1.0), (second, -poly[1])):
            if tendon < 0 or sign == 0.0:
                continue
            start = int(m.tendon_adr[tendon])
            for w in range(start, start + int(m.tendon_num[tendon])):
                if int(m.wrap_type[w]) != int(model.mj.mjtWrap.mjWRAP_JOINT):
                    return Unsupported(key, f"a coupling of tendons ({shown}) on a spatial tendon is not supported; expected fixed tendons (of joints)", line)
                joint = int(m.wrap_objid[w])
                terms[joint] = terms.get(joint, 0.0) + sign * float(m.wrap_prm[w])
    terms = {j: c for j, c in terms.items() if c != 0.0}
    if len(terms) < 2:
        held = ", ".join(clipped(model.joint_name(j)) for j in terms) or shown
        return Unsupported(key, f"an equality of {tag}s ({shown}) that holds {held} still at qpos0 (no second {tag}, or a zero slope) is not supported; "
                           "expected a coupling of two or more joint rates", line)
    if any(x != 0.0 for x in poly[2:]):
        notes.append(f"equality {tag} {clipped(model.name('mjOBJ_EQUALITY', k) or key)}{at_line(line)} is not linear (polycoef {' '.join(f'{x:g}' for x in poly)}): "
                     f"its coupling acts through its slope at qpos0, {poly[1]:g}, and holds at this pose only")
    return TreeCoupling(key, tuple(model.joint_name(j) for j in terms), tuple(terms.values()), line)


def add_coupling(model: CompiledModel, k: int, tag: str, key: str, line: int | None, notes: list[str], couplings: list[TreeCoupling], unsupported: list[Unsupported]) -> None:
    """:func:`equality_coupling` of equality ``k``, added to ``couplings`` or to ``unsupported``."""
    coupling = equality_coupling(model, k, tag, key, line, notes)
    if isinstance(coupling, Unsupported):
        unsupported.append(coupling)
    else:
        couplings.append(coupling)


def tendons_held(model: CompiledModel) -> set[int]:
    """The tendons an active tendon equality names (the others are notes of their own)."""
    m, tendon = model.m, int(model.mj.mjtEq.mjEQ_TENDON)
    return {int(o) for k in range(m.neq) if m.eq_active0[k] and int(m.eq_type[k]) == tendon for o in (m.eq_obj1id[k], m.eq_obj2id[k]) if o >= 0}
