"""The parameters of the finite-motion algorithm, each with why it has its value.

They are not thresholds of the tolerance policy (:mod:`mobility.core.tolerance`):
the policy decides ranks of matrices exact to round-off, while these judge
results of *finite* moves, exact only to ``O(step)`` (a chord of a curved
motion, a tangent space a step away).  Round-off thresholds would count those
``O(step)`` errors as directions.  Where a decision is about round-off (a
closed loop, a vanishing second-order form, a rank at the given pose) the
policy is used instead: ``tol.closure``, ``tol.rank``, ``decide_rank``.

Every number is dimensionless (radians; lengths over the mechanism's
characteristic length), so none changes when a file is scaled or moved.
"""

from __future__ import annotations

__all__ = ["DEFAULT_STEPS", "MAX_STEP_COUNT", "MAX_RANDOMS", "SAME_SUBSPACE", "MOVING_RANK", "NEARBY_RANK", "NEARBY_NEAR_SINGULAR",
           "INEXACT_ALLOWANCE", "MAX_MOVE", "DISTINCT_LINES"]

DEFAULT_STEPS = (1e-3, 1e-2, 5e-2)
"""Step sizes of the moves (joint-space distance).  Small enough that Newton
starts close to the motion, large enough that a motion that does not exist
leaves a residual of order ``h^2`` far above round-off.  Each is at most
:data:`mobility.core.poses.MAX_STEP` (1, as ``--step``)."""

MAX_STEP_COUNT = 10
"""The most step sizes ``finite_mobility`` takes (every move is re-closed at
each of them; three tell a motion from none)."""

MAX_RANDOMS = 1000
"""The most random directions ``finite_mobility`` tries besides the basis ones
(the default tries at most 14; each is a move re-closed at every step, so a
count far beyond this would not end)."""

SAME_SUBSPACE = 0.95
"""Two tangent spaces of nearby poses belong to one branch when every principal
angle between them is below acos(0.95) (18 degrees): on one branch they differ
by O(step), across branches by a finite angle."""

MOVING_RANK = 0.2
"""A direction counts among the independent moves when its singular value,
relative to the largest, exceeds this (moves are unit chords, exact to O(step))."""

NEARBY_RANK = 1e-3
"""Rank threshold at a nearby pose, as a fraction of the probe step.  Newton
pins a freedom that is infinitesimal everywhere (``x^2 = 0``) only to
``sqrt(residual)``, leaving singular values ~1e-7 that are not real, while a
pose a probe step from a singular one has its smallest singular value ~ step:
nearby poses are judged in between."""

NEARBY_NEAR_SINGULAR = 1e-2
"""Near-singular threshold at a nearby pose, as a fraction of the probe step
(above :data:`NEARBY_RANK`, for the same reason)."""

INEXACT_ALLOWANCE = 10.0
"""Geometry that is special only to ``inexact`` (the largest singular value the
rank decision dropped) leaves a first-order residual ``~ inexact * distance``
and second-order forms of relative size ``~ inexact``; this many times that
is still counted as closed (or zero), as the rank decision did."""

MAX_MOVE = 10.0
"""Newton gives up when its iterate goes farther than this many steps from its
start: it would reach another assembly, not the nearby one."""

DISTINCT_LINES = 0.999
"""Two directions found by the second-order search are the same line when
``|cos|`` of their angle is at least this."""
