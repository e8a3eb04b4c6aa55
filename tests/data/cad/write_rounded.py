"""Write a bundled mechanism as an MJCF file whose numbers are rounded to six significant digits, as a CAD exporter writes them.

Run from the repository root: ``python tests/data/cad/write_rounded.py``.  It
rewrites the files of this folder named in ``CASES``.  Each mechanism of the
library (exact, full precision) is moved rigidly (a generic rotation, so that
no axis is along x, y or z and rounding moves every axis), written in metres,
its joints cut open along a spanning tree from the ground: each tree joint a
hinge about z of its child body, the body placed and turned relative to its
parent body (``pos`` and ``quat``, as onshape-to-robot places each link
relative to the previous one, so that the rounding adds up along each
chain); each joint off the tree a closure: two ``<connect>`` equalities on its axis for an R joint (the
axis is kept: a point constraint alone would make it spherical), one for an S
joint.  Every number is written with ``%.6g``.
"""

from __future__ import annotations

import sys
from collections import deque
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parents[1]))  # tests/, for builders

import mobility  # noqa: E402
from mobility.core.transforms import Transform, rotation_from_rpy  # noqa: E402

from builders import transformed  # noqa: E402

CASES = {  # file: (library mechanism, scale to metres)
    "rounded_spherical_3rrr.xml": ("mechanisms/spherical_3rrr.yaml", 1e-3),
    "rounded_four_bar.xml": ("mechanisms/four_bar.yaml", 0.01),
}
ROTATION = rotation_from_rpy((0.3, -0.2, 1.1))


def g(values) -> str:
    return " ".join(f"{float(v):.6g}" for v in values)


def rounded(values) -> np.ndarray:
    return np.array([float(x) for x in g(values).split()])


def frame_along(z: np.ndarray) -> np.ndarray:
    """A rotation whose third column is ``z`` (unit)."""
    x = np.cross([0.31, 0.77, 0.55], z)
    x /= np.linalg.norm(x)
    return np.column_stack([x, np.cross(z, x), z])


def quaternion(r: np.ndarray) -> np.ndarray:
    """The unit quaternion (w, x, y, z) of a rotation matrix."""
    w = np.sqrt(max(0.0, 1.0 + np.trace(r))) / 2.0
    if w > 0.1:
        return np.array([w, (r[2, 1] - r[1, 2]) / (4 * w), (r[0, 2] - r[2, 0]) / (4 * w), (r[1, 0] - r[0, 1]) / (4 * w)])
    k = int(np.argmax(np.diag(r)))
    i, j = (k + 1) % 3, (k + 2) % 3
    v = np.zeros(3)
    v[k] = np.sqrt(max(0.0, 1.0 + r[k, k] - r[i, i] - r[j, j])) / 2.0
    v[i] = (r[i, k] + r[k, i]) / (4 * v[k])
    v[j] = (r[j, k] + r[k, j]) / (4 * v[k])
    return np.concatenate([[(r[j, i] - r[i, j]) / (4 * v[k])], v])


def rotation(q: np.ndarray) -> np.ndarray:
    """The rotation of a quaternion, normalised first (as MuJoCo does)."""
    w, x, y, z = np.asarray(q) / np.linalg.norm(q)
    return np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
                     [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
                     [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]])


def mjcf(path: str, scale: float) -> str:
    m = transformed(mobility.load(path), Transform(ROTATION, np.array([0.05, -0.02, 0.07])), scale)
    joints = m.world_joints
    size = 0.05  # the second anchor of an R closure: 5 cm along its axis
    parent: dict[str, tuple[str, int]] = {}
    order = [m.ground]
    queue = deque([m.ground])
    tree: set[int] = set()
    while queue:
        link = queue.popleft()
        for i, j in enumerate(joints):
            if link in j.links:
                other = j.links[1] if j.links[0] == link else j.links[0]
                if other != m.ground and other not in parent:
                    parent[other] = (link, i)
                    tree.add(i)
                    order.append(other)
                    queue.append(other)
    origin = {m.ground: np.zeros(3)}  # each body's origin and rotation as MuJoCo places it, from the rounded numbers
    turn = {m.ground: np.eye(3)}
    children: dict[str, list[str]] = {}
    for link in order[1:]:
        children.setdefault(parent[link][0], []).append(link)
    lines = ['<mujoco model="{}">'.format(Path(path).stem + " rounded to 6 digits"), '  <compiler angle="radian"/>', "  <worldbody>"]

    def body(link: str, depth: int) -> None:
        up, i = parent[link]
        j = joints[i]
        pos = rounded(turn[up].T @ (np.asarray(j.point) - origin[up]))
        exact = frame_along(np.asarray(j.axis) if j.type == "R" else turn[up][:, 2])
        quat = rounded(quaternion(turn[up].T @ exact))
        origin[link] = origin[up] + turn[up] @ pos
        turn[link] = turn[up] @ rotation(quat)
        pad = "  " * depth
        lines.append(f'{pad}<body name="{link}" pos="{g(pos)}" quat="{g(quat)}">')
        lines.append(f'{pad}  <inertial pos="0 0 0" mass="0.1" diaginertia="1e-05 1e-05 1e-05"/>')
        kind = {"R": "hinge", "S": "ball"}[j.type]
        axis = ' axis="0 0 1"' if j.type == "R" else ""
        lines.append(f'{pad}  <joint name="{j.name}" type="{kind}" pos="0 0 0"{axis}/>')
        for child in children.get(link, []):
            body(child, depth + 1)
        lines.append(f"{pad}</body>")

    for child in children.get(m.ground, []):
        body(child, 2)
    lines += ["  </worldbody>", "  <equality>"]
    for i, j in enumerate(joints):
        if i in tree:
            continue
        a, b = j.links
        anchors = [np.asarray(j.point)] + ([np.asarray(j.point) + size * np.asarray(j.axis)] if j.type == "R" else [])
        for k, p in enumerate(anchors):
            lines.append(f'    <connect name="{j.name}{"_axis" if k else ""}" body1="{a}" body2="{b}" anchor="{g(turn[a].T @ (p - origin[a]))}"/>')
    lines += ["  </equality>", "</mujoco>", ""]
    return "\n".join(lines)


if __name__ == "__main__":
    for name, (path, scale) in CASES.items():
        (HERE / name).write_text(mjcf(path, scale))
        print("wrote", HERE / name)
