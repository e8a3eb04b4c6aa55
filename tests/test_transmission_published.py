"""Transmission indices against numbers printed in a publication, within the precision printed.

Issue 34 asks for published values reproduced: a geometry and an index value,
both printed, compared within the precision the source gives.  What could be
read in a stored source (docs/sweeps.md, "Published values reproduced", lists
what was searched) is two sources, the first with two worked examples:

* S. Goessner, crocker.js 0.8.0 (2016), the crank-rocker library of his
  lectures (github.com/goessner/crocker and npmjs.com/package/crocker,
  README.md, "Node Example - Simple Crank-Rocker" and "Node Example - Optimal
  Crank-Rocker"; the README refers to his book Getriebelehre - Vektorielle
  Analyse ebener Mechanismen).  Each prints
  the link lengths of a crank-rocker (crank a, coupler b, rocker c, frame d) and
  its minimal transmission angle, reached with the crank collinear with the
  frame: a = 60, b = 103, c = 94, d = 120 give 35 deg; a = 46.7, b = 116,
  c = 73.9, d = 120 give 37.7 deg.  The bundled files are
  ``crank_rocker_goessner.yaml`` and ``crank_rocker_optimal.yaml``.

A third source adds a mechanism the two above do not cover, an offset
slider-crank: the Mechanismentechnik Wiki of Y. Pinaev and A. Fuhr (2019),
worked solutions of the exams of S. Goessner's course at the Fachhochschule
Dortmund (github.com/JerryPiper/Mechanismentechnik.github.io,
Deutsch/WS15/WS15A2_fertig/WS15A2.md, winter semester 2015, Aufgabe 2
"Schubkurbel").  Given: crank a = 35 mm, stroke 80 mm, time ratio 6/5;
printed solution: rod b = 140.5 mm, offset e = 65.2 mm and the minimal
transmission angle, cos mu_i = (a + e)/b, 44.5 deg.  The bundled file is
``slider_crank_offset.yaml``; a student's solution, not a textbook's, so the
test also checks that the printed rod and offset give back the exam's stroke
and time ratio.

The crank's output transmission index is the sine of the transmission angle
(Wang, Wu, Liu, Mech. Mach. Theory 45 (2010) 1462-1476; checked over a whole
turn in test_transmission_textbook.py), so the angle read off the sweep is
``asin(min OTI)``; a slider's OTI is the cosine of the pressure angle at the
slider, the sine of the rod's angle to the normal of the guide, the slider-crank's
transmission angle.  "Within the precision printed": a printed length is exact
only to its last digit (b = 103 is any b in [102.5, 103.5]; a and d are the
design's given values, exact), and so is a printed angle; the test asks that
the angles the library gives over every combination of those half-digit ends
reach the printed angle's interval.  The second example needs it: its
rounded lengths give 37.81 deg, the lengths before rounding 37.7 deg.
"""

from __future__ import annotations

import itertools
import math
import re

import numpy as np
import pytest

import mobility
from mobility.library import path as library_path

# name, the printed lengths {parameter: (value, half of its last printed digit)}, the printed angle and its half digit
EXAMPLES = [
    ("crank_rocker_goessner", {"a": (60.0, 0.0), "b": (103.0, 0.5), "c": (94.0, 0.5), "d": (120.0, 0.0)}, 35.0, 0.5),
    ("crank_rocker_optimal", {"a": (46.7, 0.05), "b": (116.0, 0.5), "c": (73.9, 0.05), "d": (120.0, 0.0)}, 37.7, 0.05),
]


def _least_transmission_angle(mechanism: mobility.Mechanism, count: int) -> tuple[float, float]:
    """The least transmission angle over a crank turn from the sweep's OTI, and the crank angle where it falls."""
    r = mobility.sweep(mechanism, [f"A=0:360:{count}"])
    assert r.assembled.all() and not r.singular
    i = int(np.argmin(r.oti))
    return math.degrees(math.asin(float(r.oti[i]))), float(r.values[i, 0])


def _with_lengths(name: str, lengths: dict[str, float]) -> mobility.Mechanism:
    text = library_path(name).read_text()
    for key, value in lengths.items():
        text, found = re.subn(rf"(?m)^  {key}: .*$", f"  {key}: {value!r}", text)
        assert found == 1
    return mobility.loads(text)


@pytest.mark.parametrize("name, printed, angle, half", EXAMPLES, ids=[e[0] for e in EXAMPLES])
def test_the_bundled_file_is_the_printed_geometry(name, printed, angle, half):
    m = mobility.load(library_path(name))
    points = {j.name: np.asarray(j.point) for j in m.joints}
    a, b, c, d = (printed[k][0] for k in "abcd")
    assert np.linalg.norm(points["B"] - points["A"]) == pytest.approx(a, abs=1e-9)
    assert np.linalg.norm(points["C"] - points["B"]) == pytest.approx(b, abs=1e-9)
    assert np.linalg.norm(points["D"] - points["C"]) == pytest.approx(c, abs=1e-9)
    assert np.linalg.norm(points["D"] - points["A"]) == pytest.approx(d, abs=1e-9)
    assert "github.com/goessner/crocker" in library_path(name).read_text()  # the source cited in the file


@pytest.mark.parametrize("name, printed, angle, half", EXAMPLES, ids=[e[0] for e in EXAMPLES])
def test_least_transmission_angle_over_a_crank_turn_matches_the_printed_one(name, printed, angle, half):
    ours, where = _least_transmission_angle(mobility.load(library_path(name)), 361)
    assert where == 0.0  # printed: with the crank collinear with the frame (the inner position)
    ends = [_least_transmission_angle(_with_lengths(name, dict(zip(printed, corner))), 73)[0]
            for corner in itertools.product(*[(v - h, v + h) for v, h in printed.values()])]
    low, high = min(ends), max(ends)
    assert low <= ours <= high
    assert low <= angle + half and angle - half <= high  # the printed angle's interval is reached
    assert high - low < 1.0  # and the comparison is not empty: the printed lengths pin the angle to under a degree


def test_the_simple_example_rounds_to_the_printed_degree():
    ours, _ = _least_transmission_angle(mobility.load(library_path("crank_rocker_goessner")), 361)
    assert round(ours) == 35 and abs(ours - 35.0) < 0.5


# the offset slider-crank: the printed lengths {parameter: (value, half of its last printed digit)}, a given
SLIDER = {"a": (35.0, 0.0), "b": (140.5, 0.05), "ecc": (65.2, 0.05)}
SLIDER_ANGLE, SLIDER_HALF = 44.5, 0.05


def test_the_offset_slider_crank_file_is_the_printed_geometry():
    name = "slider_crank_offset"
    m = mobility.load(library_path(name))
    points = {j.name: np.asarray(j.point) for j in m.joints}
    guide = next(j for j in m.joints if j.name == "G")
    a, b, e = (SLIDER[k][0] for k in ("a", "b", "ecc"))
    assert np.linalg.norm(points["A"] - points["O"]) == pytest.approx(a, abs=1e-9)
    assert np.linalg.norm(points["B"] - points["A"]) == pytest.approx(b, abs=1e-9)
    assert np.allclose(guide.axis, [1, 0, 0]) and points["B"][1] - points["O"][1] == pytest.approx(-e, abs=1e-9)
    assert "github.com/JerryPiper/Mechanismentechnik.github.io" in library_path(name).read_text()
    # the printed rod and offset give back the exam's givens: stroke 80 mm, forth/back ratio 6/5 (16.36 deg printed)
    assert math.sqrt((b + a) ** 2 - e**2) - math.sqrt((b - a) ** 2 - e**2) == pytest.approx(80.0, abs=0.05)
    assert math.degrees(math.asin(e / (b - a)) - math.asin(e / (b + a))) == pytest.approx(180 * (6 - 5) / (6 + 5), abs=0.005)


def _least_slider_angle(mechanism: mobility.Mechanism, count: int) -> tuple[float, float]:
    """The least transmission angle over a crank turn (the crank is joint O) and the crank angle where it falls."""
    r = mobility.sweep(mechanism, [f"O=0:360:{count}"])
    assert r.assembled.all() and not r.singular
    i = int(np.argmin(r.oti))
    return math.degrees(math.asin(float(r.oti[i]))), float(r.values[i, 0])


def test_least_transmission_angle_of_the_offset_slider_crank_matches_the_printed_one():
    ours, where = _least_slider_angle(mobility.load(library_path("slider_crank_offset")), 361)
    assert where == 90.0  # the crank normal to the guide, pointing away from it (the file's crank is along x)
    ends = [_least_slider_angle(_with_lengths("slider_crank_offset", dict(zip(SLIDER, corner))), 73)[0]
            for corner in itertools.product(*[(v - h, v + h) for v, h in SLIDER.values()])]
    low, high = min(ends), max(ends)
    assert low <= ours <= high
    assert low <= SLIDER_ANGLE + SLIDER_HALF and SLIDER_ANGLE - SLIDER_HALF <= high  # the printed angle's interval is reached
    assert round(ours, 1) == SLIDER_ANGLE  # at the printed lengths the angle rounds to the printed one
    assert high - low < 0.2  # and the comparison is not empty
