"""Mechanisms built in code for the tests, and a seeded random-mechanism generator."""

from __future__ import annotations

import dataclasses
import json
import math
from typing import Any

import numpy as np

from mobility.core.model import Frame, Joint, Mechanism
from mobility.core.transforms import Transform, rotation_from_axis_angle


ONE_WIRE_FLEXURE = """\
name: one wire
units: {length: mm, modulus: GPa}
ground: base
end_effector: stage
materials:
  steel: {E: 200, nu: 0.3}
elements:
  - {name: w1, type: rod, bodies: [base, stage], axis: [0, 0, 1], length: 100, radius: 1, material: steel}
"""
"""A flexure document of one steel wire from the base to the stage, to which a test adds or changes keys."""


THREE_RPS_YAML = """
name: 3-RPS
ground: base
end_effector: platform
units: {length: mm}
parameters: {rb: 200, rp: 100, h: 150}
limbs:
  - copies: 3
    joints:
      - {name: "R{i+1}", type: R, links: [base, "leg{i+1}"], axis: ["-sind(120*i)", "cosd(120*i)", 0],
         point: ["rb*cosd(120*i)", "rb*sind(120*i)", 0]}
      - {name: "P{i+1}", type: P, links: ["leg{i+1}", "rod{i+1}"],
         axis: ["(rp-rb)*cosd(120*i)", "(rp-rb)*sind(120*i)", "h"]}
      - {name: "S{i+1}", type: S, links: ["rod{i+1}", platform], point: ["rp*cosd(120*i)", "rp*sind(120*i)", "h"]}
"""
"""A 3-RPS written with a limb pattern (R tangent at the base, P along the leg, S on the platform)."""


def unit(v) -> tuple[float, float, float]:
    v = np.asarray(v, dtype=float)
    return tuple(v / np.linalg.norm(v))


def four_bar(points=((0, 0, 0), (1, 2, 0), (4, 2.5, 0), (5, 0, 0))) -> Mechanism:
    """Planar four-bar (the spec's example by default)."""
    a, b, c, d = points
    z = (0, 0, 1)
    return Mechanism(
        "four-bar",
        "ground",
        "coupler",
        (
            Joint("A", "R", ("ground", "crank"), axis=z, point=a),
            Joint("B", "R", ("crank", "coupler"), axis=z, point=b),
            Joint("C", "R", ("coupler", "rocker"), axis=z, point=c),
            Joint("D", "R", ("rocker", "ground"), axis=z, point=d),
        ),
    )


def three_prs(heights=(0.5, 0.5, 0.5), rb=1.0, rp=0.5, leg=1.0) -> Mechanism:
    """3-PRS: vertical sliders at radius rb, R axes tangent, S joints at radius rp.

    With equal heights the platform is at its symmetric pose.  With unequal
    heights the S centres are placed consistently with rigid legs: the S point
    of leg i lies in the plane of its R joint (radial-vertical plane) at leg
    length ``leg`` from the R axis; the platform is not required to be an
    equilateral triangle here (a different, still valid 3-PRS).
    """
    joints = []
    for i in range(3):
        th = 2 * np.pi * i / 3
        e = np.array([np.cos(th), np.sin(th), 0.0])
        t = np.array([-np.sin(th), np.cos(th), 0.0])
        r_point = rb * e + np.array([0, 0, heights[i]])
        dz = np.sqrt(leg**2 - (rb - rp) ** 2)
        s_point = rp * e + np.array([0, 0, heights[i] + dz])
        joints += [
            Joint(f"P{i + 1}", "P", ("base", f"slider{i + 1}"), axis=(0, 0, 1)),
            Joint(f"R{i + 1}", "R", (f"slider{i + 1}", f"leg{i + 1}"), axis=tuple(t), point=tuple(r_point)),
            Joint(f"S{i + 1}", "S", (f"leg{i + 1}", "platform"), point=tuple(s_point)),
        ]
    return Mechanism("3-PRS", "base", "platform", tuple(joints))


def six_ups(rb=1.0, rp=0.6, h=1.2) -> Mechanism:
    """Stewart platform with U-P-S legs, 6 DOF."""
    joints = []
    for k in range(6):
        pair, side = divmod(k, 2)
        ab = np.radians(120 * pair + (-15 if side == 0 else 15))
        ap = np.radians(120 * pair + (-45 if side == 0 else 45))
        b = np.array([rb * np.cos(ab), rb * np.sin(ab), 0.0])
        p = np.array([rp * np.cos(ap), rp * np.sin(ap), h])
        joints += [
            Joint(f"U{k + 1}", "U", ("base", f"cyl{k + 1}"), point=tuple(b), axes=((1, 0, 0), (0, 1, 0))),
            Joint(f"P{k + 1}", "P", (f"cyl{k + 1}", f"rod{k + 1}"), axis=tuple(p - b)),
            Joint(f"S{k + 1}", "S", (f"rod{k + 1}", "platform"), point=tuple(p)),
        ]
    return Mechanism("6-UPS", "base", "platform", tuple(joints))


def transformed(m: Mechanism, tf: Transform, scale: float = 1.0) -> Mechanism:
    """``m`` with every joint moved rigidly by ``tf`` after scaling lengths by ``scale``."""
    joints = []
    for j in m.world_joints:
        changes = {}
        if j.point is not None:
            changes["point"] = tuple(tf.apply_point(np.asarray(j.point) * scale))
        if j.axis is not None:
            changes["axis"] = tuple(tf.apply_vector(j.axis))
        if j.normal is not None:
            changes["normal"] = tuple(tf.apply_vector(j.normal))
        if j.axes is not None:
            changes["axes"] = tuple(tuple(tf.apply_vector(a)) for a in j.axes)
        if j.pitch is not None:
            changes["pitch"] = j.pitch * scale
        joints.append(Joint(j.name, j.type, j.links, **{**_geometry(j), **changes}))
    return m.replace(joints=tuple(joints), frames=())


def scaled(m: Mechanism, factor: float) -> Mechanism:
    """``m`` with every length (points, pitches) times ``factor``, written in the global frame (every other field kept)."""
    joints = []
    for j in m.world_joints:
        changes: dict[str, Any] = {}
        if j.point is not None:
            changes["point"] = tuple(float(x) * factor for x in j.point)
        if j.pitch is not None:
            changes["pitch"] = j.pitch * factor
        joints.append(dataclasses.replace(j, **changes))
    return m.replace(joints=tuple(joints), frames=())


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


def _geometry(j: Joint) -> dict:
    return {k: getattr(j, k) for k in ("axis", "point", "pitch", "axes", "normal") if getattr(j, k) is not None}


def random_rotation(rng: np.random.Generator) -> np.ndarray:
    axis = rng.normal(size=3)
    return rotation_from_axis_angle(axis / np.linalg.norm(axis), rng.uniform(-np.pi, np.pi))


def random_joint(rng: np.random.Generator, name: str, links: tuple[str, str], special: bool) -> Joint:
    """A random joint; with ``special``, directions and points come from a small set (paradox-prone)."""
    jtype = rng.choice(list("RRRPPHCUSE"))
    if special:
        axis = [(0, 0, 1), (1, 0, 0), (0, 1, 0)][rng.integers(3)]
        point = tuple(float(x) for x in rng.integers(-2, 3, size=3))
    else:
        axis = unit(rng.normal(size=3))
        point = tuple(rng.uniform(-2, 2, size=3))
    if jtype in "R":
        return Joint(name, "R", links, axis=axis, point=point)
    if jtype == "P":
        return Joint(name, "P", links, axis=axis)
    if jtype == "H":
        return Joint(name, "H", links, axis=axis, point=point, pitch=float(rng.uniform(-0.5, 0.5)))
    if jtype == "C":
        return Joint(name, "C", links, axis=axis, point=point)
    if jtype == "U":
        a2 = unit(np.cross(axis, rng.normal(size=3))) if not special else [(1, 0, 0), (0, 1, 0), (0, 0, 1)][(int(np.argmax(np.abs(axis))) + 1) % 3]
        return Joint(name, "U", links, point=point, axes=(axis, a2))
    if jtype == "S":
        return Joint(name, "S", links, point=point)
    return Joint(name, "E", links, normal=axis, point=point)


def random_mechanism(seed: int, *, bridge: bool | None = None) -> Mechanism:
    """A random mechanism: 1-4 limbs of 1-5 joints between ground and end effector.

    Half the seeds use special geometry (axes along x, y, z, integer points),
    which produces the parallel and intersecting axes of paradox mechanisms.
    Some add a tie link between two limbs (a graph that is not series-parallel)
    or a chain hanging off a limb.
    """
    rng = np.random.default_rng(seed)
    special = bool(rng.integers(2))
    joints: list[Joint] = []
    limbs = int(rng.integers(1, 5))
    inner: list[list[str]] = []
    for k in range(limbs):
        n = int(rng.integers(1, 6))
        chain = ["ground"] + [f"l{k}_{i}" for i in range(n - 1)] + ["ee"]
        inner.append(chain[1:-1])
        for i in range(n):
            joints.append(random_joint(rng, f"J{k}_{i}", (chain[i], chain[i + 1]), special))
    with_bridge = bridge if bridge is not None else bool(rng.integers(3) == 0)
    candidates = [limb for limb in inner if limb]
    if with_bridge and len(candidates) >= 2:
        a = candidates[0][int(rng.integers(len(candidates[0])))]
        b = candidates[1][int(rng.integers(len(candidates[1])))]
        joints.append(random_joint(rng, "T1", (a, "tie"), special))
        joints.append(random_joint(rng, "T2", ("tie", b), special))
    if rng.integers(4) == 0 and candidates:
        a = candidates[0][0]
        joints.append(random_joint(rng, "D1", (a, "dangling"), special))
    order = rng.permutation(len(joints))
    return Mechanism(f"random-{seed}", "ground", "ee", tuple(joints[i] for i in order))


def with_frame_wrapper(m: Mechanism, tf: Transform) -> Mechanism:
    """``m`` with every joint written in a frame placed at ``tf`` (same world geometry moved by tf)."""
    frame = Frame("moved", tuple(tf.translation), tuple(map(tuple, tf.rotation)))
    joints = tuple(Joint(j.name, j.type, j.links, frame="moved", **_geometry(j)) for j in m.world_joints)
    return m.replace(joints=joints, frames=(frame,))


def normalised(m: Mechanism, screws_rows: np.ndarray) -> np.ndarray:
    """Screws given as rows in global coordinates, as columns in ``m``'s normalised coordinates.

    Subspaces of screws must be compared there: in file units a screw system
    mixes lengths and directions, and no tolerance fits every unit.
    """
    from mobility.core.joint_screws import joint_screws

    return joint_screws(m).normalisation.from_world(np.asarray(screws_rows).T)


# -- large families (tests/test_large.py and benchmarks/bench_large.py) ---------------------------------

Z = (0.0, 0.0, 1.0)


def triangle_ladder(triangles: int, actuated: bool = False) -> Mechanism:
    """A planar ladder: ``A{i}: R [g, l{i}]`` on the ground line, ``B{i}: R [l{i}, l{i+1}]`` above it (every triangle rigid).

    With ``actuated``, the first pivot ``A0`` is an input.
    """
    joints = [Joint(f"A{i}", "R", ("g", f"l{i}"), axis=Z, point=(float(i), 0.0, 0.0), actuated=actuated and i == 0) for i in range(triangles + 1)]
    joints += [Joint(f"B{i}", "R", (f"l{i}", f"l{i + 1}"), axis=Z, point=(i + 0.5, 1.0 + 0.25 * math.sin(i), 0.0)) for i in range(triangles)]
    return Mechanism(f"ladder of {triangles}", "g", f"l{triangles}", tuple(joints))


def serial_chain(count: int) -> Mechanism:
    """A serial chain of ``count`` revolute joints with axes in general position."""
    joints = []
    for i in range(count):
        a = "g" if i == 0 else f"l{i}"
        b = "e" if i == count - 1 else f"l{i + 1}"
        axis = (math.cos(0.7 * i), math.sin(0.7 * i), 0.3 * math.cos(1.3 * i) + 0.1)
        joints.append(Joint(f"J{i}", "R", (a, b), axis=axis, point=(0.01 * i, math.sin(i), math.cos(0.5 * i))))
    return Mechanism(f"chain of {count}", "g", "e", tuple(joints))


def prs_limbs(limbs: int, actuated: bool = False) -> Mechanism:
    """A parallel mechanism of ``limbs`` P-R-S limbs around a circle (3 DOF, 1T2R, whatever the count).

    With ``actuated``, the first three sliders are the inputs.
    """
    joints = []
    for i in range(limbs):
        c, s = math.cos(2 * math.pi * i / limbs), math.sin(2 * math.pi * i / limbs)
        joints.append(Joint(f"P{i}", "P", ("g", f"a{i}"), axis=Z, actuated=actuated and i < 3))
        joints.append(Joint(f"R{i}", "R", (f"a{i}", f"b{i}"), axis=(-s, c, 0.0), point=(c, s, 0.5)))
        joints.append(Joint(f"S{i}", "S", (f"b{i}", "e"), point=(0.5 * c, 0.5 * s, 1.0)))
    return Mechanism(f"{limbs}-PRS", "g", "e", tuple(joints))


def flat_3rps(height: float = 0.0) -> str:
    """Lee and Shah's 3-RPS (base radius 200 mm, platform 100 mm) with its platform ``height`` mm above the base plane.

    At height 0 every leg lies in the platform's plane: actuation and constraint
    forces are coplanar, an actuation singularity with three uncontrolled
    freedoms whose two sides are both valid.
    """
    return f"""
name: 3-RPS with its platform {height:g} mm above the base plane
ground: base
end_effector: platform
units: {{angle: deg, length: mm}}
limbs:
  - copies: 3
    frame: {{name: "leg{{i+1}}", rpy: [0, 0, "120*i"]}}
    joints:
      - {{name: "R{{i+1}}", type: R, links: [base, "cyl{{i+1}}"], axis: [0, 1, 0], point: [200, 0, 0]}}
      - {{name: "P{{i+1}}", type: P, links: ["cyl{{i+1}}", "pis{{i+1}}"], axis: [-100, 0, {height!r}], actuated: true}}
      - {{name: "S{{i+1}}", type: S, links: ["pis{{i+1}}", platform], point: [100, 0, {height!r}]}}
"""
