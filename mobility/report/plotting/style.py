"""The look of the pictures, the same in every figure (and in the 3D view): one symbol per joint type, one colour per role."""

from __future__ import annotations

from typing import TypedDict

from ...errors import clipped

__all__ = ["JOINT_STYLE", "COLORS", "LIMB_COLORS", "MAX_LABEL", "MAX_TITLE", "drawn_name"]

MAX_TITLE = 500
"""The most characters of a title drawn (a longer one is cut, ``...`` marking the cut); the lines that do not fit the figure are cut too."""

MAX_LABEL = 40
"""The most characters of a name (a link's, a joint's, a mechanism's, a swept coordinate's) that a picture writes.

matplotlib lays out every glyph of a text: a name of 200,000 characters (a file allows megabytes) takes a minute
to draw.  The pictures write its start, the cut marked by ``...``; the text reports keep every name whole.
"""


def drawn_name(name: object) -> str:
    """``name`` as a picture writes it: at most :data:`MAX_LABEL` characters, a longer one cut and marked by ``...``.

    Examples
    --------
    >>> drawn_name("crank"), len(drawn_name("J" * 200_000)), drawn_name("J" * 200_000)[-4:]
    ('crank', 40, 'J...')
    """
    return clipped(name, MAX_LABEL)


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
