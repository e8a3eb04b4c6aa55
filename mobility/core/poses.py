"""Assembled poses of a mechanism away from its given one, by a seeded random walk.

The poses ``mobility actuation --samples`` and ``mobility view --samples``
look at besides the file's own.
"""

from __future__ import annotations

import numpy as np

from ..errors import RequestError, shown_argument
from .kinematics import kinematics
from .couplings import require_no_couplings
from .model import Mechanism, require_mechanism
from .validation import require_integer, require_real
from .tolerance import DEFAULT_TOLERANCE, Tolerance, require_tolerance

__all__ = ["sample_poses", "require_pose_count", "require_seed", "require_step", "step_value", "DEFAULT_STEP", "MAX_STEP", "MAX_SAMPLED_POSES"]

MAX_SAMPLED_POSES = 100_000
"""Most poses :func:`sample_poses` is asked for (each a Newton solve; ``--samples`` stops at 1,000)."""

DEFAULT_STEP = 0.1
"""The default step of :func:`sample_poses` and ``--step`` (radians; lengths over the characteristic length)."""

MAX_STEP = 1.0
"""The largest step of a move (:func:`sample_poses`, :func:`mobility.finite.finite_mobility`, ``--step``).

A joint-space distance: a radian, or the characteristic length.  A larger
move is no step along the motion (Newton would reach another assembly)."""


def require_step(value: object, caller: str = "sample_poses", argument: str = "step") -> float:
    """``value`` as a ``float`` when it is a step of a move: a real number (not a bool) in ``(0, MAX_STEP]``, else a :class:`RequestError`.

    Examples
    --------
    >>> require_step(np.float32(0.5))
    0.5
    >>> require_step(1e300)
    Traceback (most recent call last):
    mobility.errors.RequestError: sample_poses: step: expected a joint-space distance in (0, 1] (radians; lengths over the characteristic length), got 1e+300
    >>> require_step("0.1")
    Traceback (most recent call last):
    mobility.errors.RequestError: step: expected a positive joint-space distance, got '0.1'
    """
    try:
        number = require_real(value, "")
        if 0.0 < number <= MAX_STEP:
            return number
    except RequestError:  # not a finite real number: an integer beyond the floats is still a step too large
        try:
            number = require_integer(value, "", low=1)
        except RequestError:
            number = 0.0
    if number > 0.0:
        raise RequestError(caller=caller, argument=argument, got=shown_argument(value),
                           expected=f"a joint-space distance in (0, {MAX_STEP:g}] (radians; lengths over the characteristic length)")
    raise RequestError(argument=argument, expected="a positive joint-space distance", got=shown_argument(value))


def step_value(value: object) -> float | None:
    """:func:`require_step` for a test: ``value`` as a ``float`` when it is a step, else None (kept for the callers of the public name).

    Examples
    --------
    >>> step_value(np.float32(0.5)), step_value(0), step_value(1e300), step_value("0.1"), step_value(b"a")
    (0.5, None, None, None, None)
    """
    try:
        return require_step(value)
    except RequestError:
        return None


def require_seed(value: object, key: str = "seed") -> int:
    """``value`` as the seed of a random choice: a non-negative integer; else a :class:`RequestError` naming ``key``.

    None is refused: every result of the package is reproducible.

    Examples
    --------
    >>> require_seed(np.int64(3))
    3
    >>> require_seed(None, "finite_mobility: seed")
    Traceback (most recent call last):
    mobility.errors.RequestError: finite_mobility: seed: expected a non-negative integer, got None
    """
    return require_integer(value, "a non-negative integer", argument=key, low=0)


def require_pose_count(value: object, key: str = "count") -> int:
    """``value`` as a number of poses to sample: an integer (not a bool) in ``[0, MAX_SAMPLED_POSES]``; else a :class:`RequestError` naming ``key``.

    Examples
    --------
    >>> require_pose_count(np.int64(3), "samples")
    3
    >>> require_pose_count(2.5, "samples")
    Traceback (most recent call last):
    mobility.errors.RequestError: samples: expected a number of poses in [0, 100,000], got 2.5
    """
    return require_integer(value, f"a number of poses in [0, {MAX_SAMPLED_POSES:,}]", argument=key, low=0, high=MAX_SAMPLED_POSES)


def sample_poses(mechanism: Mechanism, count: int, *, step: float = DEFAULT_STEP, seed: int = 0, tol: Tolerance = DEFAULT_TOLERANCE) -> list[Mechanism]:
    """Assembled poses reached by moving ``mechanism`` from its given pose.

    Seeded: each pose starts from one already reached, moves ``step`` along a
    random first-order motion and re-closes every loop by Newton (a move that
    does not close is retried with half the step, down to ``step / 8``); it is
    rebuilt as a :class:`~mobility.core.model.Mechanism` in the global frame,
    so the parametrisation never degenerates.

    Parameters
    ----------
    step : float
        Joint-space distance of each move in ``(0, MAX_STEP]`` (radians;
        lengths over the characteristic length: the same for a scaled file).
    seed : int
        A non-negative integer (None is refused).
    tol : Tolerance
        The rank policy and closure threshold.

    Returns
    -------
    list of Mechanism
        Up to ``count`` poses closed to round-off; fewer (possibly none) when
        the mechanism cannot move from where it is.

    Examples
    --------
    >>> import mobility
    >>> poses = sample_poses(mobility.load("mechanisms/slider_crank.yaml"), 3, step=0.2, seed=1)
    >>> len(poses), all(p.joints[0].point == (0.0, 0.0, 0.0) and abs(p.joints[2].point[1]) < 1e-9 for p in poses)
    (3, True)
    """
    mechanism = require_mechanism(mechanism, "sample_poses")
    require_no_couplings(mechanism.couplings, mechanism.name, "sample_poses", "sampled poses")
    tol = require_tolerance(tol, "sample_poses")
    count = require_pose_count(count)
    step = require_step(step)
    rng = np.random.default_rng(require_seed(seed))
    reached: list[Mechanism] = [mechanism]
    out: list[Mechanism] = []
    failures = 0
    while len(out) < count and failures < 20 * max(count, 1):
        start = reached[int(rng.integers(len(reached)))]
        kin = kinematics(start)
        _, null = kin.rank_decision(np.zeros(kin.variable_count), tol)
        if null.shape[1] == 0:
            if start is mechanism:
                break  # nothing moves from the given pose
            failures += 1
            continue
        u = rng.standard_normal(null.shape[1])
        d = null @ (u / np.linalg.norm(u))
        h = step
        while h >= step / 8.0:
            closure = kin.close(h * d, constraints=(d[None, :], np.array([h])), tol=tol, max_move=10.0 * h)
            if closure.converged:
                moved = kin.mechanism_at(closure.q)
                reached.append(moved)
                out.append(moved)
                break
            h /= 2.0
        else:
            failures += 1
    return out
