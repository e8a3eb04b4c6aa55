"""Parallel mechanisms assembled from synthesized limbs, and their mechanism files.

:func:`pkm_document` checks a PKM with :func:`mobility.analyze` before writing its
file (:func:`mobility.io.writer.mechanism_to_yaml`).

Examples
--------
>>> from mobility.synthesis.enumeration import synthesize
>>> result = synthesize("3R", verify_samples=0)
>>> m = assemble_pkm(result, "S", copies=3)
>>> [j.type for j in m.joints]
['S', 'U', 'P', 'S', 'U', 'P', 'S', 'U', 'P', 'S']
>>> print(pkm_document(result, "S", copies=3)[1].splitlines()[-1])
expected: {dof: 3, pattern: 3R, mobility: 3}
"""

from __future__ import annotations

import contextlib
import math
import os
from dataclasses import replace
from pathlib import Path
from typing import Any, Sequence

import numpy as np

from ..core.analysis import analyze, gruebler_kutzbach
from ..core.model import Joint, Mechanism
from ..core.validation import require_instance, require_integer, require_real
from ..core.screws import helical_twist, prismatic_twist
from ..core.linalg import rank
from ..errors import RequestError, SynthesisError, counted, name_list, shown_argument
from ..io.limits import current_limits
from ..io.writer import mechanism_to_yaml
from ..outputs import atomic_output
from .enumeration import SynthesisResult
from .limb_types import CandidateJoint, joint_groups

__all__ = ["assemble_pkm", "pkm_document", "write_pkm_files"]


def _limb_joints(groups: Sequence[tuple[str, list[CandidateJoint]]], points: dict[str, np.ndarray], prefix: str, base: str, end: str) -> list[Joint]:
    """Mechanism joints of a limb from its groups (S and U become one joint each)."""
    out = []
    links = [base] + [f"{prefix}{k + 1}" for k in range(len(groups) - 1)] + [end]
    for k, (g, members) in enumerate(groups):
        a, b = links[k], links[k + 1]
        first = members[0]
        name = f"{prefix}_{g}" if sum(1 for h, _ in groups if h == g) == 1 else f"{prefix}_{g}{k + 1}"
        if g == "S":
            out.append(Joint(name, "S", (a, b), point=tuple(points[first.point])))
        elif g == "U":
            out.append(Joint(name, "U", (a, b), point=tuple(points[first.point]), axes=(members[0].joint.axis, members[1].joint.axis)))
        elif first.joint.kind == "P":
            out.append(Joint(name, "P", (a, b), axis=first.joint.axis))
        else:
            out.append(Joint(name, "R", (a, b), axis=first.joint.axis, point=tuple(points[first.point])))
    return out


def _regular_at_home(joints: Sequence[Joint], origin: np.ndarray, length: float) -> bool:
    """Whether the limb's freedoms are independent at its home pose (twists about ``origin``, lengths over ``length``)."""
    twists = []
    for j in joints:
        for f in j.freedoms():
            point = (np.asarray(f.point) - origin) / length
            twists.append(prismatic_twist(f.axis) if f.kind == "P" else helical_twist(f.axis, point, f.pitch / length))
    matrix = np.array(twists).T
    return rank(matrix) == matrix.shape[1]


def assemble_pkm(result: SynthesisResult, structure: str, *, other: str = "UPS", copies: int = 4, base_radius: float = 600.0,
                 platform_radius: float = 400.0, height: float = 900.0, twist_deg: float = 60.0,
                 twist_pattern: Sequence[float] = (1.0, 0.0, 1.0, 2.0), name: str | None = None) -> Mechanism:
    """A PKM of one synthesized limb and ``copies`` 6-DOF limbs, as a :class:`~mobility.core.model.Mechanism`.

    The first realisation of ``structure`` (a name in ``result``) is used as
    found, with the pattern's point ``O`` where the pattern put it (the base
    centre, for a machine) and its generic points (``g1, g2, ...``) moved onto
    the line through ``O`` along ``s1``, at distances ``height``, ``height/2``,
    ``height/4``...  (for a machine, synthesize with ``s1`` vertical, e.g.
    ``directions=((0, 0, 1), (0, 1, 0))``).  The 6-DOF limbs are ``UPS`` (U on
    the base with a vertical and a tangential axis, S on the platform) or
    ``SPRR`` (S on the base, then two R on the platform, the first horizontal
    and normal to the leg, the second vertical: each R normal to the axis
    before it, so the limb reaches every orientation), attached at ``base_radius`` in the plane through ``O``
    normal to z and, turned by ``twist_deg``, at ``platform_radius`` and
    ``height``.  Every 6-DOF limb's P is actuated, and so is the first P of
    the synthesized limb (its last R if it has none; none if it has neither).

    ``copies`` keeps the PKM within :attr:`~mobility.io.limits.Limits.max_joints`.

    Raises
    ------
    SynthesisError
        For an unknown ``other`` limb, a ``structure`` that is not in
        ``result``, or a limb singular at its home pose.
    RequestError
        For an argument of the wrong type or out of its range (each named).
    """
    result = require_instance(result, SynthesisResult, "assemble_pkm: result", "mobility.synthesize")
    if other not in ("UPS", "SPRR"):
        raise SynthesisError(caller="other", expected="UPS or SPRR", got=shown_argument(other))
    if not isinstance(structure, str):
        raise RequestError(caller="assemble_pkm", argument="structure", expected="the name of a limb type of the result (a str)", got=type(structure).__name__)
    if name is not None and not isinstance(name, str):
        raise RequestError(caller="assemble_pkm", argument="name", expected="a str or None", got=type(name).__name__)
    found = result.structure(structure)
    copies = _copies(copies, result.joints, 3 if other == "UPS" else 4)
    base_radius, platform_radius, height = (_length(v, key) for v, key in ((base_radius, "base_radius"), (platform_radius, "platform_radius"), (height, "height")))
    twist = require_real(twist_deg, "a finite number of degrees", caller="assemble_pkm", argument="twist_deg")
    pattern = _twist_pattern(twist_pattern)
    plane = tuple(k for k in result.directions if k.startswith("s"))
    s1 = np.array(result.directions.get("s1", (0.0, 0.0, 1.0)))
    # any axis not along s1 gives a normal to it; 0.9 only keeps the cross product well away from zero
    s2 = np.array(result.directions.get("s2", np.cross(s1, [1.0, 0.0, 0.0]) if abs(s1[0]) < 0.9 else np.cross(s1, [0.0, 1.0, 0.0])))
    s2 = s2 - (s2 @ s1) * s1
    s2 /= np.linalg.norm(s2)
    origin = np.array(result.points.get("O", (0.0, 0.0, 0.0)))
    joints: list[Joint] = []
    for offset in (0.0, 0.25):  # first g on the line through O along s1, then every g off it
        points: dict[str, np.ndarray] = {k: np.array(v) for k, v in result.points.items()}
        for label in points:
            if label.startswith("g"):  # off one line through O, so that two Rc do not lose rank at home
                k = int(label[1:]) - 1
                points[label] = origin + height / 2**k * s1 + (offset if k == 0 else (-1) ** k / 4) * height * s2
        for seq in found.realizations:
            joints = _limb_joints(joint_groups(seq, plane), points, "L0", "base", "platform")
            if _regular_at_home(joints, origin, height):
                break
        else:
            continue
        break
    else:
        raise SynthesisError(f"every realisation of {structure} is singular at its home pose (all joint values zero) with these points")
    acted = next((j for j in joints if j.type == "P"), None) or next((j for j in reversed(joints) if j.type == "R"), None)
    joints = [replace(j, actuated=j is acted) for j in joints]
    for i in range(copies):
        phi = math.radians(45.0 + 360.0 * i / copies)
        psi = phi + math.radians(twist) * pattern[i % len(pattern)]
        a = origin + np.array([base_radius * math.cos(phi), base_radius * math.sin(phi), 0.0])
        b = origin + np.array([platform_radius * math.cos(psi), platform_radius * math.sin(psi), height])
        tangent_a = np.array([-math.sin(phi), math.cos(phi), 0.0])
        across = np.cross(b - a, [0.0, 0.0, 1.0])
        across /= np.linalg.norm(across)
        up = np.array([0.0, 0.0, 1.0])
        k = i + 1
        leg = Joint(f"P{k}", "P", (f"L{k}a", f"L{k}b"), axis=tuple(b - a), actuated=True)
        if other == "UPS":
            joints += [Joint(f"U{k}", "U", ("base", f"L{k}a"), point=tuple(a), axes=(tuple(up), tuple(tangent_a))), leg,
                       Joint(f"S{k}", "S", (f"L{k}b", "platform"), point=tuple(b))]
        else:
            joints += [Joint(f"S{k}", "S", ("base", f"L{k}a"), point=tuple(a)), leg,
                       Joint(f"R{k}a", "R", (f"L{k}b", f"L{k}c"), axis=tuple(across), point=tuple(b)),
                       Joint(f"R{k}b", "R", (f"L{k}c", "platform"), axis=tuple(up), point=tuple(b))]
    return Mechanism(name or f"{found.name}-{copies}({other})", "base", "platform", tuple(joints))


def _copies(value: object, limb_joints: int, per_copy: int) -> int:
    """``copies`` of :func:`assemble_pkm`: an integer from 1 to as many as keep the PKM within the joints a file may have; else a :class:`RequestError`.

    Examples
    --------
    >>> _copies(4, 5, 3)
    4
    >>> _copies(0, 5, 3)
    Traceback (most recent call last):
    mobility.errors.RequestError: assemble_pkm: copies: expected an integer from 1 to 1665 (5 joints of the limb and 3 per copy within the limit of 5000 joints: set MOBILITY_MAX_JOINTS to raise it), got 0
    """
    limits = current_limits()
    most = max(1, (limits.max_joints - limb_joints) // per_copy)
    return require_integer(value, f"an integer from 1 to {most} ({counted(limb_joints, 'joint')} of the limb and {per_copy} per copy "
                                  f"within the limit of {counted(limits.max_joints, 'joint')}: {limits.hint('max_joints')})",
                           caller="assemble_pkm", argument="copies", low=1, high=most)


def _length(value: object, key: str) -> float:
    """A length of :func:`assemble_pkm`: a finite positive number, else a :class:`RequestError` naming ``key``."""
    return require_real(value, "a finite positive length", caller="assemble_pkm", argument=key, positive=True)


def _twist_pattern(value: object) -> tuple[float, ...]:
    """``twist_pattern`` of :func:`assemble_pkm`: a non-empty sequence of finite numbers (at most 1000), else a :class:`RequestError`.

    Examples
    --------
    >>> _twist_pattern(())
    Traceback (most recent call last):
    mobility.errors.RequestError: assemble_pkm: twist_pattern: expected a non-empty sequence of finite numbers (at most 1000), got ()
    """
    items = (value if isinstance(value, Sequence) and not isinstance(value, (str, bytes)) and len(value) <= 1000 else
             value.tolist() if isinstance(value, np.ndarray) and value.ndim == 1 and value.size <= 1000 else ())
    try:
        numbers = tuple(require_real(x, "") for x in items)
    except RequestError:
        numbers = ()
    if not numbers:
        raise RequestError(caller="assemble_pkm", argument="twist_pattern", expected="a non-empty sequence of finite numbers (at most 1000)", got=shown_argument(value))
    return numbers


def pkm_document(result: SynthesisResult, structure: str, *, other: str = "UPS", **geometry: Any) -> tuple[Mechanism, str]:
    """A PKM assembled by :func:`assemble_pkm`, analysed, and its mechanism file text.

    The ``expected`` block comes from the synthesis (DOF and pattern of the
    pattern, mobility the Grübler-Kutzbach count); :func:`mobility.analyze` must agree.

    Raises
    ------
    SynthesisError
        When the limb cannot be assembled at its home pose, or the analyzer
        disagrees with the expected values.
    """
    mechanism = assemble_pkm(result, structure, other=other, **geometry)
    found = result.structure(structure)
    pattern_text = result.pattern.name
    expected = {"dof": result.pattern.dim, "pattern": pattern_text, "mobility": gruebler_kutzbach(mechanism)}
    r = analyze(mechanism)
    if (r.dof, r.pattern, r.mobility) != (expected["dof"], expected["pattern"], expected["mobility"]):
        raise SynthesisError(f"{structure}: the analyzer finds {r.dof} DOF {r.pattern}, mobility {r.mobility} for the assembled PKM, not {expected}")
    table = " It is one of the seven 5-DOF limbs of Table 1 of that paper." if found.in_table_1 else " It is not in Table 1 of that paper; the enumeration found it."
    description = (f"A {expected['dof']}-DOF parallel mechanism of one {found.name} limb and {mechanism.name.split('-', 1)[1]} limbs, "
                   f"assembled by mobility.assemble_pkm from the type synthesis of the {result.pattern.name} pattern "
                   f"({result.pattern.description}) after T. Sun, S. Yang, T. Huang, J. S. Dai, 'A Finite and Instantaneous Screw "
                   f"Based Approach for Topology Design and Kinematic Analysis of 5-Axis Parallel Kinematic Machines', Chinese "
                   f"Journal of Mechanical Engineering 31:44 (2018).{table} Conditions of the limb: {'; '.join(found.conditions)}. "
                   f"Dimensions are illustrative (mm). Expected: the limb's finite motions are the {pattern_text} pattern and the "
                   f"6-DOF limbs add no constraint, so the platform has {expected['dof']} DOF, {pattern_text}; the mobility is the "
                   f"Grübler-Kutzbach count (no redundant constraint).")
    return mechanism, mechanism_to_yaml(mechanism, description=description, expected=expected)


def write_pkm_files(result: SynthesisResult, folder: str | Path, *, other: str = "UPS") -> tuple[tuple[str, ...], tuple[str, ...]]:
    """Write one mechanism file per limb type of ``result``: ``pkm_<limb>_4<other>.yaml`` in ``folder``.

    Each file is a :func:`pkm_document` with four ``other`` limbs; a limb type
    that cannot be assembled (singular at its home pose) is skipped.

    Returns
    -------
    written, skipped : tuple of str
        The paths written; one line per limb type not assembled, with why.

    Raises
    ------
    RequestError
        When ``folder`` cannot be created or written (then no file of this call
        is left), a file to write is already there (nothing is written), or the
        chains of ``result`` are shorter than the pattern's dimension.
    """
    result = require_instance(result, SynthesisResult, "write_pkm_files: result", "mobility.synthesize")
    if not isinstance(folder, (str, os.PathLike)):
        raise RequestError(caller="write_pkm_files", argument="folder", expected="a folder name (str or path)", got=type(folder).__name__)
    path = Path(folder)
    if result.joints != result.pattern.dim:
        raise RequestError(f"{folder}: a PKM is assembled from limbs of {counted(result.pattern.dim, 'joint')} (the dimension of {result.pattern.name}); "
                           f"these chains have {result.joints}")
    written: list[str] = []
    skipped: list[str] = []
    documents: list[tuple[Path, str]] = []
    for s in result.structures:
        try:
            _, text = pkm_document(result, s.name, other=other)
        except SynthesisError as exc:
            skipped.append(f"{s.name}: {exc}")
            continue
        documents.append((path / f"pkm_{s.name.lower()}_4{other.lower()}.yaml", text))
    present = [str(target) for target, _ in documents if os.path.lexists(target)]
    if present:  # a file written before may have been annotated by hand since
        raise RequestError(f"{folder}: would overwrite {name_list(present, most=3)}; write to a new folder, or remove them first")
    try:
        path.mkdir(exist_ok=True)
        for target, text in documents:  # each file whole or not at all (mobility.outputs)
            with atomic_output(target) as handle:
                handle.write(text)
            written.append(str(target))
    except BaseException as exc:  # all or nothing: the files this call wrote are removed (a full disk, an interrupt)
        for done in written:
            with contextlib.suppress(OSError):
                os.unlink(done)
        if isinstance(exc, OSError):
            raise RequestError(f"{folder}: cannot write mechanism files there ({exc.strerror or exc})") from None
        raise
    return tuple(written), tuple(skipped)
