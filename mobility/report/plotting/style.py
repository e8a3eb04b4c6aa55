"""The look of the pictures: one symbol per joint type, one colour per role.

Every picture uses these, so a joint type, a freedom or a constraint looks the
same in every figure (and in other views that import them).
"""

from __future__ import annotations

from typing import TypedDict

__all__ = ["JOINT_STYLE", "COLORS", "LIMB_COLORS"]


class JointStyle(TypedDict):
    """How one joint type is drawn (an entry of :data:`JOINT_STYLE`)."""

    marker: str
    s: int
    facecolor: str
    label: str


JOINT_STYLE: dict[str, JointStyle] = {
    "R": {"marker": "o", "s": 46, "facecolor": "white", "label": "R revolute"},
    "P": {"marker": "s", "s": 46, "facecolor": "#ffe08a", "label": "P prismatic"},
    "H": {"marker": "8", "s": 52, "facecolor": "#c8e6c9", "label": "H helical"},
    "C": {"marker": "D", "s": 40, "facecolor": "#d1c4e9", "label": "C cylindrical"},
    "U": {"marker": "P", "s": 70, "facecolor": "#90caf9", "label": "U universal"},
    "S": {"marker": "o", "s": 70, "facecolor": "#37474f", "label": "S spherical"},
    "E": {"marker": "h", "s": 64, "facecolor": "#ffccbc", "label": "E planar"},
}
"""matplotlib marker, size, fill and legend label of each joint type."""

COLORS = {
    "ground": "#5d5d5d",
    "end_effector": "#ef6c00",
    "link": "#4f7cac",
    "translation": "#1b8a3a",
    "rotation": "#1565c0",
    "force": "#c62828",
    "couple": "#8e24aa",
}
"""Colour of each role: links by kind, freedoms and constraint wrenches."""

LIMB_COLORS = ("#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e", "#17becf", "#8c564b", "#e377c2", "#bcbd22", "#7f7f7f")
"""Colours of the branches (limbs) of the joint graph, in turn."""
