"""The words of the 3D view: hover text of each screw and joint, the title of a pose.

Numbers as in the text report (:mod:`mobility.report.text`), in the file's units; lines joined by plotly's ``<br>``.

Examples
--------
>>> import mobility
>>> r = mobility.analyze(mobility.load("mechanisms/scara.yaml"))
>>> translation_text(1, r.translations[0])
'T1 translation<br>direction [1, 0, 0]'
>>> rotation_text(1, r.rotations[0], r.length_scale, r.length_unit)
'R1 rotation<br>axis [0, 0, 1]<br>through [560, 300, 250] mm<br>pitch 0'
>>> pose_title(r)
'SCARA arm (serial Schönflies 3T1R): end effector 4 DOF (3T1R), mobility 4 (Grübler–Kutzbach 4)'
"""

from __future__ import annotations

import html
from collections import Counter
from typing import Any, Sequence

import numpy as np

from ..core.model import JOINT_TYPES, Joint
from ..core.result import Result, ScrewAxis
from ..report.text import fmt_number, fmt_vector

__all__ = ["translation_text", "rotation_text", "couple_text", "force_text", "joint_text", "pose_title", "margin_text", "header_lines", "plotly_text"]


def _length(value: Any, scale: float, unit: str) -> str:  # a number, or a vector (a sequence or an array)
    text = fmt_vector(value, scale) if np.ndim(value) else fmt_number(float(value), scale)
    return f"{text} {unit}" if unit else text


def translation_text(number: int, direction: np.ndarray) -> str:
    """Hover text of the translation ``T<number>``."""
    return f"T{number} translation<br>direction {fmt_vector(direction)}"


def rotation_text(number: int, axis: ScrewAxis, scale: float, unit: str) -> str:
    """Hover text of the rotational freedom ``R<number>``: axis, point, pitch (length per radian)."""
    pitch = "0" if axis.pitch == 0 else fmt_number(axis.pitch, scale) + (f" {unit}/rad" if unit else " per rad")
    return f"R{number} {axis.kind}<br>axis {fmt_vector(axis.axis)}<br>through {_length(axis.point, scale, unit)}<br>pitch {pitch}"


def couple_text(number: int, direction: np.ndarray) -> str:
    """Hover text of the constraint couple ``C<number>``."""
    return f"C{number} constraint couple<br>about {fmt_vector(direction)}"


def force_text(number: int, axis: ScrewAxis, scale: float, unit: str) -> str:
    """Hover text of the constraint wrench ``W<number>``: a force line, and its couple's pitch if any."""
    text = f"W{number} constraint {axis.kind}<br>along {fmt_vector(axis.axis)}<br>through {_length(axis.point, scale, unit)}"
    if axis.pitch != 0:
        text += f"<br>couple pitch {_length(axis.pitch, scale, unit)}"
    return text


def plotly_text(text: object) -> str:
    """``text`` as Plotly shows it written (``gr<b>o</b>und`` not in bold): its ``<``, ``>`` and ``&`` as entities.

    Examples
    --------
    >>> plotly_text("crank<i>&</i>")
    'crank&lt;i&gt;&amp;&lt;/i&gt;'
    """
    return html.escape(str(text), quote=False)


def joint_text(joint: Joint, located: bool, scale: float, unit: str) -> str:
    """Hover text of a joint: name, type, links, axis or axes, point."""
    lines = [f"{plotly_text(joint.name)}: {joint.type} {JOINT_TYPES[joint.type]}", f"links {plotly_text(joint.links[0])} – {plotly_text(joint.links[1])}"]
    if joint.axis is not None:
        lines.append(f"axis {fmt_vector(joint.axis)}")
    if joint.axes is not None:
        lines.append("axes " + ", ".join(fmt_vector(a) for a in joint.axes))
    if joint.normal is not None:
        lines.append(f"normal {fmt_vector(joint.normal)}")
    if joint.pitch is not None:
        lines.append(f"pitch {_length(joint.pitch, scale, unit)}")
    lines.append(f"through {_length(joint.point, scale, unit)}" if located else "no point in the file: drawn between its links")
    return "<br>".join(lines)


def margin_text(result: Result) -> str:
    """The rank margin in a few words, with the near-singular and inexact flags."""
    text = f"margin {result.margin.smallest_kept:.2e}"
    if result.margin.near_singular:
        text += " (near-singular)"
    if result.margin.inexact:
        text += " (inexact geometry)"
    return text


def pose_title(result: Result, label: str = "") -> str:
    """One line: name (and pose label), DOF, pattern, mobility and the Grübler–Kutzbach count."""
    where = f" — {label}" if label else ""
    return f"{result.name}{where}: end effector {result.dof} DOF ({result.pattern}), mobility {result.mobility} (Grübler–Kutzbach {result.gruebler_kutzbach})"


def header_lines(results: Sequence[Result], labels: Sequence[str]) -> list[str]:
    """The lines under the title of a page: units, the explanation of G–K, warnings; per pose for several."""
    first = results[0]
    lines = []
    if first.length_unit:
        lines.append(f"lengths in {first.length_unit}; pitches of freedoms in {first.length_unit}/rad, of wrenches in {first.length_unit}")
    if len(results) == 1:
        lines.append(f"constraint wrenches on the end effector: {6 - first.dof}; {margin_text(first)}")
        if first.gruebler_kutzbach_explanation:
            lines.append("why Grübler–Kutzbach differs: " + first.gruebler_kutzbach_explanation)
        lines += [f"warning: {w}" for w in first.warnings]
        return lines
    counts = Counter(r.pattern for r in results)
    lines.append(f"{len(results)} poses; patterns: " + ", ".join(f"{p} × {n}" for p, n in counts.items()))
    flagged = [lab for r, lab in zip(results, labels) if r.margin.near_singular]
    if flagged:
        lines.append("near-singular: " + ", ".join(flagged))
    return lines
