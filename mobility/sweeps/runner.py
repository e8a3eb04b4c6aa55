"""``mobility.sweep``: close and analyse every pose of a grid, in chunks, where it is told.

Two stages, each in independent chunks: closure (:mod:`mobility.sweeps.continuation`)
and analysis. Chunks run on ``workers`` threads of this process (the stacked
LAPACK calls release the GIL) or on a dask.distributed cluster
(``pip install 'mechanism-mobility[dask]'``); within a chunk, in blocks of :data:`BLOCK`.

Examples
--------
>>> import mobility
>>> r = sweep(mobility.load("mechanisms/3prs.yaml"), ["P1=-20:20:3", "P2=-20:20:3"])
>>> r.shape, r.counts()
((3, 3), {(3, '1T2R', 3): 9})
"""

from __future__ import annotations

import contextlib
import inspect
import itertools
import logging
import math
import os
import socket
import sys
import threading
from concurrent.futures import FIRST_COMPLETED, ThreadPoolExecutor, wait
from dataclasses import dataclass
from functools import cached_property
from typing import Any, Callable, Generator, Iterable, Iterator, Sequence, cast
from urllib.parse import urlsplit

import numpy as np

from ..core.joint_screws import joint_screws
from ..core.model import Mechanism, require_mechanism
from ..core.validation import require_bool, require_integer
from ..core.screw_systems import analyse_poses
from ..core.tolerance import DEFAULT_TOLERANCE, Tolerance, require_tolerance
from ..core.topology import decompose
from ..errors import MissingExtraError, RequestError, clipped, shown_argument
from .batch_actuation import ActuationInputs, actuated_inputs, actuation_at_poses
from ..core.kinematics import Kinematics, kinematics
from .seams import find_seams
from .batch_transmission import GOOD_TRANSMISSION, transmission_columns, transmission_threshold
from .continuation import GridClosure, close_lines, line_layout, anchors, seed_grid, targets_of
from .steps import Drive, polish, residuals
from .grid_closure import fill
from .grid import DEFAULT_MAX_POSES, GridPlan, VarySpec, plan_grid
from .posed_screws import posed_screws
from .result import TRANSMISSION, SweepResult
from .walks import axis_walk

__all__ = ["sweep", "analyse_joint_variables", "tqdm_progress", "DEFAULT_CHUNK_SIZE", "BLOCK", "MAX_WORKERS", "Progress"]

DEFAULT_CHUNK_SIZE = 50_000
"""Poses per chunk (a unit of work sent to a worker)."""

BLOCK = 8192
"""Poses analysed together inside a chunk (keeps the stacked arrays in cache)."""

IN_FLIGHT = 2
"""Chunks per worker handed out at a time (the rest wait, unbuilt, so memory stays bounded)."""

WAKE_SECONDS = 0.1
"""How often a sweep waiting for its chunks looks for an interrupt (Ctrl-C)."""

MAX_WORKERS = 256
"""Most threads a sweep runs its chunks on in this process (more only wait for the same cores)."""

Progress = Callable[[str, int, int], None]
"""``progress(stage, done, total)``: called as chunks finish (stage ``"closing loops"`` or ``"analysing"``)."""


@dataclass(frozen=True, eq=False)
class _Context:
    """Everything a chunk needs; sent once to each worker."""

    mechanism: Mechanism
    plan: GridPlan
    tol: Tolerance
    inputs: ActuationInputs | None
    transmission: float | None = GOOD_TRANSMISSION  # the good-transmission threshold; None: no transmission indices

    @cached_property
    def bk(self) -> Kinematics:
        return kinematics(self.mechanism)

    def __getstate__(self) -> dict:
        state = dict(vars(self))
        state.pop("bk", None)  # rebuilt where it is used (pickle puts the rest back into __dict__, past the frozen __setattr__)
        return state


_STOP = threading.local()
"""The event that tells a chunk running on a thread of this process to stop (set when the sweep is interrupted)."""


def _stop_if_asked(_: int = 0) -> None:
    """Raise :class:`KeyboardInterrupt` in a chunk whose sweep was interrupted: its work is dropped at the next step or block."""
    event = getattr(_STOP, "event", None)
    if event is not None and event.is_set():
        raise KeyboardInterrupt("the sweep was interrupted")


def _stoppable(event: threading.Event, function: Callable, *args: Any) -> Any:
    """``function(*args)`` on a worker thread, stopping at its next step or block once ``event`` is set."""
    _STOP.event = event
    try:
        return function(*args)
    finally:
        _STOP.event = None


def close_chunk(context: _Context, starts_q: np.ndarray, starts_ok: np.ndarray, lines: np.ndarray, anchor: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Close a chunk of lines of the last axis by continuation (a task)."""
    axes = context.plan.axes
    drive = Drive.of(axes, context.bk.variable_count)
    walk = axis_walk(axes[-1], len(axes) - 1)
    return close_lines(context.bk, drive, starts_q, starts_ok, targets_of(context.plan, lines), anchor, walk=walk, tol=context.tol, on_step=_stop_if_asked)


def analyse_chunk(context: _Context, q: np.ndarray) -> dict[str, np.ndarray]:
    """Analyse a chunk of assembled poses (a task): the columns of the table."""
    parts = []
    for start in range(0, len(q), BLOCK):
        _stop_if_asked()
        block = q[start : start + BLOCK]
        posed = posed_screws(context.bk, block)
        answers = analyse_poses(decompose(context.mechanism), posed.twists, posed.offsets, context.tol)
        out = {key: getattr(answers, key) for key in ("dof", "pattern", "mobility", "smallest_kept", "largest_dropped", "near_singular", "inexact")}
        if context.inputs is not None:
            act = actuation_at_poses(context.mechanism, posed, answers, context.inputs, context.tol)
            out.update(verdict=act.verdict, conditioning=act.conditioning, actuation_margin=act.margin)
            out.update(transmission_columns(context.mechanism, posed, answers, act, context.inputs, context.tol) if context.transmission is not None else {})
        parts.append(out)
    if not parts:
        return {}
    return {key: np.concatenate([p[key] for p in parts]) for key in parts[0]}


def analyse_grid_chunk(context: _Context, rows: np.ndarray, q: np.ndarray) -> dict[str, np.ndarray]:
    """Analyse a chunk of assembled grid points (a task): the columns, and the poses polished.

    A pose whose rank decision lies in the warning band (``near_singular`` or
    ``inexact``, where a float64 closure's round-off can decide it) is polished
    (:func:`~mobility.sweeps.steps.polish`) and analysed again. ``"polished"``
    holds their positions in ``rows``, ``"q_polished"`` and ``"residual_polished"`` their values.
    """
    columns = analyse_chunk(context, q)
    doubtful = np.flatnonzero(columns["near_singular"] | columns["inexact"]) if columns else np.zeros(0, dtype=int)
    polished, residual = q[doubtful], np.zeros(doubtful.size)
    if doubtful.size:
        drive = Drive.of(context.plan.axes, context.bk.variable_count)
        targets = targets_of(context.plan, rows[doubtful])
        polished = polish(context.bk, drive, polished, targets)
        residual = residuals(context.bk, drive, polished, targets)
        again = analyse_chunk(context, polished)
        for key, values in again.items():
            columns[key][doubtful] = values
    return {**columns, "polished": doubtful, "q_polished": polished, "residual_polished": residual}


def analyse_joint_variables(mechanism: Mechanism, q: np.ndarray, *, actuated: Sequence[str] | None = None, tol: Tolerance = DEFAULT_TOLERANCE, transmission: bool = True) -> dict[str, np.ndarray]:
    """The sweep's analysis of given poses: the table's columns for joint variables ``q`` ``(N, n)``.

    The poses are taken as they are (``q`` should close the loops, e.g. rows of
    :attr:`SweepResult.q`). With inputs (``actuated``, or marked in the file),
    also ``verdict``, ``conditioning``, ``actuation_margin`` and (unless
    ``transmission=False``) ``iti``, ``oti``, ``lti``, ``cti``.

    Examples
    --------
    >>> import numpy as np, mobility
    >>> m = mobility.load("mechanisms/3prs.yaml")
    >>> analyse_joint_variables(m, np.zeros((2, 15)))["pattern"].tolist()
    ['1T2R', '1T2R']
    """
    caller = "analyse_joint_variables"
    mechanism = require_mechanism(mechanism, caller)
    tol = require_tolerance(tol, caller)
    transmission = require_bool(transmission, caller=caller, argument="transmission")
    q = _require_joint_variables(q, joint_screws(mechanism).offsets[-1], caller)
    plan = GridPlan((), joint_screws(mechanism).normalisation.length)
    inputs = actuated_inputs(mechanism, actuated)  # default: the joints marked actuated (none: no actuation columns)
    return analyse_chunk(_Context(mechanism, plan, tol, inputs if inputs.freedoms else None, GOOD_TRANSMISSION if transmission else None), q)


def _require_joint_variables(q: Any, n: int, caller: str) -> np.ndarray:
    """``q`` as a float array ``(N, n)`` of finite joint variables, ``N >= 1``, else a RequestError naming ``caller``."""
    expected = f"finite real joint variables of shape (N, {n}), N at least 1"
    try:
        array = np.asarray(q, dtype=float)
    except (TypeError, ValueError):
        raise RequestError(caller=caller, argument="q", expected=expected, got=shown_argument(q)) from None
    if array.ndim != 2 or array.shape[0] < 1 or array.shape[1] != n:
        raise RequestError(caller=caller, argument="q", expected=expected, got=f"shape {array.shape}")
    if not np.isfinite(array).all():
        raise RequestError(caller=caller, argument="q", expected=expected, got="a NaN or an infinity")
    return array


CONNECT_SECONDS = 10.0
"""How long a sweep waits for a dask scheduler to answer before giving up."""


@contextlib.contextmanager
def _quiet_distributed() -> Iterator[None]:
    """distributed's loggers silenced for the duration (their levels restored after)."""
    names = ["distributed"] + [n for n in list(logging.root.manager.loggerDict) if n.startswith("distributed.")]
    loggers = [logging.getLogger(n) for n in names]
    saved = [lg.level for lg in loggers]
    for lg in loggers:
        lg.setLevel(logging.CRITICAL + 1)
    try:
        yield
    finally:
        for lg, level in zip(loggers, saved):
            lg.setLevel(level)


def _connect(distributed: Any, address: str) -> Any:
    """A ``distributed.Client`` of the scheduler at ``address``, or a :class:`RequestError` within :data:`CONNECT_SECONDS`.

    Made on a daemon thread: a server that never answers the handshake would hold the sweep forever.
    """
    refused = _refused(address)
    if refused:
        raise RequestError(f"cannot reach a dask scheduler there ({refused})", argument=f"--scheduler {address}")
    box: dict[str, Any] = {}

    def connect() -> None:
        try:
            box["client"] = distributed.Client(address, timeout=f"{CONNECT_SECONDS}s")
        except Exception as exc:  # reported below, on the caller's thread
            box["error"] = exc

    thread = threading.Thread(target=connect, name="mobility-dask-connect", daemon=True)
    with _quiet_distributed():  # a server that is not a scheduler makes distributed log tracebacks; the error below says it in one line
        thread.start()
        thread.join(CONNECT_SECONDS + 2.0)
    if "client" in box:
        return box["client"]
    why = f"{type(box['error']).__name__}: {box['error']}" if "error" in box else f"no answer within {CONNECT_SECONDS:g} s"
    raise RequestError(f"cannot reach a dask scheduler there ({why})", argument=f"--scheduler {address}")


def _refused(address: str) -> str:
    """Why a TCP scheduler address cannot be connected to ('' when it can, or is not plain TCP), said before dask's retries."""
    parts = urlsplit(address if "://" in address else f"tcp://{address}")
    if parts.scheme != "tcp":
        return ""
    try:
        host, port = parts.hostname, parts.port
    except ValueError as exc:  # a port out of range or not a number
        return str(exc)
    if not host or port is None:
        return ""
    try:
        socket.create_connection((host, port), timeout=CONNECT_SECONDS).close()
    except OSError as exc:
        return exc.strerror or str(exc) or type(exc).__name__
    return ""


class _Runner:
    """Runs chunks in-process (threads) or on a dask.distributed cluster, reporting progress."""

    def __init__(self, context: _Context, scheduler: Any, workers: int | None, progress: Progress | None) -> None:
        self.context = context
        self.progress = progress
        self.client: Any = None  # a dask.distributed Client (untyped), or None
        self._owns_client = False
        if scheduler is not None:
            try:
                from dask import distributed
            except ImportError as exc:
                raise MissingExtraError("running a sweep on a dask cluster", "dask[distributed]", "dask", str(exc)) from None
            if isinstance(scheduler, str):
                self.client = _connect(distributed, scheduler)
                self._owns_client = True
            else:
                self.client = scheduler
            self.workers = len(self.client.scheduler_info().get("workers", {}))
            if self.workers == 0:
                self.close()
                raise RequestError("the dask scheduler has no workers; start some (dask worker ADDRESS) and run again", argument=f"--scheduler {scheduler}")
            self._context_future = self.client.scatter(context, broadcast=True)
        else:
            self.workers = max(1, workers if workers is not None else (os.cpu_count() or 1))

    def close(self) -> None:
        if self._owns_client and self.client is not None:
            self.client.close()

    def run(self, stage: str, function: Callable, chunks: Iterable[tuple], weights: Sequence[int]) -> Generator[tuple[int, Any], None, None]:
        """``(i, function(context, *chunk))`` for every chunk, as they finish.

        ``chunks`` is consumed lazily, at most :data:`IN_FLIGHT` per worker out
        at a time: memory beyond the table stays a few chunks' worth.
        """
        total, done = int(sum(weights)), 0
        if self.progress:
            self.progress(stage, 0, total)
        serial = self.client is None and self.workers == 1
        finished = ((i, function(self.context, *chunk)) for i, chunk in enumerate(chunks)) if serial else self._bounded(function, iter(enumerate(chunks)))
        try:
            for i, result in finished:
                done += weights[i]
                if self.progress:
                    self.progress(stage, done, total)
                yield i, result
        finally:  # closed with this generator (an interrupt in its consumer): the chunks in flight stop now, not at exit
            finished.close()

    def _bounded(self, function: Callable, numbered: Iterator[tuple[int, tuple]]) -> Generator[tuple[int, Any], None, None]:
        limit = IN_FLIGHT * self.workers
        if self.client is not None:
            from dask import distributed

            position: dict[Any, int] = {}
            queue = distributed.as_completed()

            def submit(i: int, chunk: tuple) -> None:
                future = self.client.submit(function, self._context_future, *chunk, pure=False)
                position[future.key] = i
                queue.add(future)

            for i, chunk in itertools.islice(numbered, limit):
                submit(i, chunk)
            for future in queue:  # as_completed takes futures added while it is iterated
                i = position.pop(future.key)
                for j, chunk in itertools.islice(numbered, 1):
                    submit(j, chunk)
                yield i, future.result()
            return
        stop = threading.Event()
        pool = ThreadPoolExecutor(self.workers)
        try:
            running = {pool.submit(_stoppable, stop, function, self.context, *chunk): i for i, chunk in itertools.islice(numbered, limit)}
            while running:
                # a short timeout: a signal taken by another thread (numpy's) does not wake a wait without one, and an
                # interrupt then waited for the next chunk to finish (minutes for a big one)
                finished, _ = wait(running, timeout=WAKE_SECONDS, return_when=FIRST_COMPLETED)
                for future in finished:
                    i = running.pop(future)
                    for j, chunk in itertools.islice(numbered, 1):
                        running[pool.submit(_stoppable, stop, function, self.context, *chunk)] = j
                    yield i, future.result()
        finally:  # an interrupt (or an error) stops the chunks in flight at their next step and drops those waiting
            stop.set()
            pool.shutdown(wait=True, cancel_futures=True)


def _split(count: int, pieces: int) -> list[np.ndarray]:
    return [part for part in np.array_split(np.arange(count), max(1, min(pieces, count))) if part.size]


def tqdm_progress() -> Progress:
    """A progress bar on stderr for each stage (needs tqdm: ``pip install 'mechanism-mobility[progress]'``).

    Raises
    ------
    MissingExtraError
        When tqdm is not installed.
    """
    try:
        from tqdm import tqdm
    except ImportError as exc:
        raise MissingExtraError("a progress bar", "tqdm", "progress", str(exc)) from None
    bars: dict[str, Any] = {}

    def update(stage: str, done: int, total: int) -> None:
        bar = bars.get(stage)
        if bar is None:
            bar = bars[stage] = tqdm(total=total, desc=stage, unit="pose", file=sys.stderr, leave=False, dynamic_ncols=True)
        bar.update(done - bar.n)
        if done >= total:
            bar.close()

    return update


def sweep(mechanism: Mechanism, vary: VarySpec | Iterable, *, actuated: Sequence[str] | None = None, tol: Tolerance = DEFAULT_TOLERANCE,
          max_poses: int = DEFAULT_MAX_POSES, chunk_size: int = DEFAULT_CHUNK_SIZE, scheduler: Any = None, workers: int | None = None,
          progress: bool | Progress | None = None, transmission: bool = True, good_threshold: float = GOOD_TRANSMISSION) -> SweepResult:
    """Mobility, singularities and actuation over a grid of poses.

    At every point of the product grid the other joints are solved so that
    every loop closes (continuation from the file's pose), and the pose is
    analysed as :func:`mobility.analyze` (with inputs, :func:`mobility.check_actuation`) would.

    Parameters
    ----------
    mechanism : Mechanism
        The mechanism at its given pose (the grid's displacements start there).
    vary : str, sequence or mapping
        ``"NAME=START:STOP:COUNT"`` (or several), ``(name, start, stop,
        count)`` tuples, or ``{name: (start, stop, count)}``: a joint (degrees
        for R, H, C; the file's length unit for P) or an end-effector pose
        coordinate ``x y z`` (length) ``rx ry rz`` (degrees).
    actuated : sequence of str, optional
        The inputs whose verdict and conditioning are wanted; default: the
        joints marked ``actuated: true`` (none: no actuation columns).
    tol : Tolerance
        The rank policy and the closure tolerance.
    max_poses, chunk_size : int
        Refuse a larger grid; poses per chunk of work.
    scheduler : distributed.Client or str, optional
        Run the chunks on a dask.distributed cluster (a client, or a
        scheduler's address); default: in this process.
    workers : int, optional
        Threads in this process (default: the number of CPUs).
    progress : bool or callable, optional
        ``True``: a progress bar on stderr (tqdm); a callable
        ``progress(stage, done, total)``; default: none.
    transmission, good_threshold : bool, float
        With inputs, also the indices of :mod:`mobility.transmission` (``False``: not), and their good-transmission threshold (0.7).

    Raises
    ------
    RequestError
        A bad request (see :func:`mobility.sweeps.grid.plan_grid`), or a
        scheduler that cannot be reached.
    MechanismError
        An actuated name that is not a joint.
    MissingExtraError
        A scheduler without dask, or a progress bar without tqdm.
    """
    if not isinstance(mechanism, Mechanism):
        raise RequestError(caller="sweep", expected="a Mechanism (from mobility.load)", got=type(mechanism).__name__)
    tol = require_tolerance(tol, "sweep")
    chunk_size, max_poses = (_positive_integer(key, value) for key, value in (("chunk_size", chunk_size), ("max_poses", max_poses)))
    workers = None if workers is None else _positive_integer("workers", workers)
    if workers is not None and workers > MAX_WORKERS:
        raise RequestError(f"sweep: workers must be at most {MAX_WORKERS} (threads of this process), got {clipped(str(workers))}; "
                           "for more, run the chunks on a dask cluster (scheduler)")
    _require_scheduler(scheduler)
    _require_progress(progress)
    plan = plan_grid(mechanism, vary, max_poses=max_poses)
    chosen = actuated_inputs(mechanism, actuated)  # default: the joints marked actuated
    inputs = chosen if chosen.freedoms else None
    report = tqdm_progress() if progress is True else (progress or None)
    context = _Context(mechanism, plan, tol, inputs, transmission_threshold(transmission, good_threshold, inputs is not None))
    runner = _Runner(context, scheduler, workers, report)
    try:
        closure = _close(context, runner, chunk_size)
        columns = _analyse(context, runner, closure, chunk_size)
    finally:
        runner.close()
    return _result(context, closure, columns)


def _positive_integer(key: str, value: Any) -> int:
    """``value`` as an ``int`` when it is a positive integer (not a bool), else a :class:`RequestError`."""
    try:
        return require_integer(value, "", low=1)
    except RequestError:
        raise RequestError(f"{key} must be a positive integer, got {shown_argument(value)}", caller="sweep") from None


def _require_scheduler(scheduler: Any) -> None:
    """``None``, an address, or a ``distributed.Client`` (anything with ``submit`` and ``scheduler_info``)."""
    if scheduler is None or isinstance(scheduler, str):
        return
    if not (callable(getattr(scheduler, "submit", None)) and callable(getattr(scheduler, "scheduler_info", None))):
        raise RequestError(f"scheduler must be a dask distributed.Client or a scheduler's address, got {type(scheduler).__name__}", caller="sweep")


def _require_progress(progress: Any) -> None:
    """``None``, a bool, or a callable taking ``(stage, done, total)``."""
    if progress is None or isinstance(progress, bool):
        return
    if not callable(progress):
        raise RequestError(f"progress must be True, False or a callable progress(stage, done, total), got {type(progress).__name__}", caller="sweep")
    try:
        inspect.signature(progress).bind("stage", 0, 1)
    except TypeError:
        raise RequestError("progress must accept three arguments, progress(stage, done, total)", caller="sweep") from None
    except ValueError:  # no signature to read (some builtins): take it as it is
        pass


def _close(context: _Context, runner: _Runner, chunk_size: int) -> GridClosure:
    plan = context.plan
    closure = seed_grid(context.bk, plan, tol=context.tol)  # this sweep's own arrays, filled in place from here on
    q, err, ok = closure.q, closure.residual, closure.assembled
    shape = plan.shape
    layout = line_layout(shape, len(shape) - 1)
    anchor = anchors(plan)[-1]
    starts = layout[:, anchor]
    pieces = max(math.ceil(plan.size / chunk_size), runner.workers if len(layout) >= 64 * runner.workers else 1)
    groups = _split(len(layout), pieces)
    chunks = ((q[starts[g]], ok[starts[g]], layout[g], anchor) for g in groups)
    with contextlib.closing(runner.run("closing loops", close_chunk, chunks, [layout[g].size for g in groups])) as finished:
        for i, (lq, lerr, lok) in finished:
            lines = layout[groups[i]]
            q[lines], err[lines], ok[lines] = lq, lerr, lok
    return fill(context.bk, plan, closure, tol=context.tol)


UNANSWERED = {"dof": (-1, int), "pattern": ("", object), "mobility": (-1, int), "smallest_kept": (np.nan, float), "largest_dropped": (np.nan, float),
              "near_singular": (False, bool), "inexact": (False, bool), "verdict": ("", object), "conditioning": (np.nan, float),
              "actuation_margin": (np.nan, float), **dict.fromkeys(TRANSMISSION, (np.nan, float))}
"""Each column's value (and type) at a pose that is not analysed (not assembled, or no input chosen)."""


def _analyse(context: _Context, runner: _Runner, closure: GridClosure, chunk_size: int) -> dict[str, np.ndarray]:
    """The table's columns over the whole grid; polished poses replace theirs in ``closure.q`` (the sweep's own array)."""
    keys = [key for key in UNANSWERED if (context.inputs is not None or key not in ("verdict", "conditioning", "actuation_margin")) and (key not in TRANSMISSION or context.transmission is not None)]
    columns: dict[str, np.ndarray] = {key: np.full(context.plan.size, *UNANSWERED[key]) for key in keys}
    rows = np.flatnonzero(closure.assembled)
    pieces = max(math.ceil(rows.size / chunk_size), runner.workers if rows.size >= 2 * BLOCK * runner.workers else 1)
    groups = [rows[g] for g in _split(rows.size, pieces)] if rows.size else []
    chunks = ((g, closure.q[g]) for g in groups)
    with contextlib.closing(runner.run("analysing", analyse_grid_chunk, chunks, [g.size for g in groups])) as finished:
        for i, result in finished:
            g = groups[i]
            polished = g[result.pop("polished")]
            closure.q[polished] = result.pop("q_polished")
            closure.residual[polished] = result.pop("residual_polished")
            for key, values in result.items():
                columns[key][g] = values
    return columns


def _result(context: _Context, closure: GridClosure, columns: dict[str, np.ndarray]) -> SweepResult:
    actuation: dict[str, Any] = {} if context.inputs is None else {"actuated": context.inputs.names}
    return SweepResult(mechanism=context.mechanism, axes=context.plan.axes, q=closure.q, assembled=closure.assembled, residual=closure.residual,
                       tolerance=context.tol, good_threshold=GOOD_TRANSMISSION if context.transmission is None else context.transmission,
                       seams=find_seams(context.bk, context.plan, closure.q, closure.assembled, tol=context.tol),
                       **cast("dict[str, Any]", columns), **actuation)  # the table's columns, each a field of the result
