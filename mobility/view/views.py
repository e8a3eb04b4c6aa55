"""The interactive 3D view of a mechanism's freedoms and constraints, for a page or a notebook.

:func:`mechanism_view` shows one pose, :func:`poses_view` several with a slider.  A :class:`View` writes one
self-contained HTML page (:meth:`View.write_html`) and shows itself in Jupyter, the text report as its plain-text part.

Examples
--------
>>> import mobility
>>> m = mobility.load("mechanisms/3prs.yaml")
>>> v = mechanism_view(m)
>>> v.frames[0].result.pattern, [g.key for g in v.scenes[0].layer("freedoms")]
('1T2R', ['T1', 'R1', 'R2'])
>>> v.answer
'end effector 3 DOF, pattern 1T2R; mobility 3 (Grübler–Kutzbach count 3)'
"""

from __future__ import annotations

import itertools
from collections.abc import Sized
from dataclasses import dataclass
from functools import cached_property
from pathlib import Path
from typing import Any, Iterable

from ..core.analysis import analyze
from ..core.joint_screws import joint_screws
from ..core.model import Mechanism, require_mechanism
from ..core.validation import require_integer
from ..core.result import Result, require_result_of
from ..core.tolerance import DEFAULT_TOLERANCE, Tolerance, require_tolerance
from ..errors import MissingExtraError, RequestError, counted, shown_argument
from ..outputs import atomic_output
from ..report.plotting.backend import written_file_name
from ..report.plotting.sketch import drawing_scale
from ..report.text import text_report
from .describe import header_lines, margin_text
from .figure import figure_dict as build_figure_dict
from .page import offline_mimebundle, page_html, require_plotly, screws_table
from .scene import Scene, build_scene

__all__ = ["ViewFrame", "View", "mechanism_view", "poses_view", "require_max_poses", "MAX_POSES"]


@dataclass(frozen=True, eq=False)
class ViewFrame:
    """One pose of a view: the mechanism at that pose, its analysis, and a label for the slider."""

    mechanism: Mechanism
    result: Result
    label: str = ""


@dataclass(frozen=True, eq=False)
class View:
    """An interactive 3D view of one or several poses.

    ``scenes``: what is drawn for each frame; ``notes``: what the header says of
    the poses besides their answers (a sweep's poses not drawn, and why).
    """

    frames: tuple[ViewFrame, ...]
    scenes: tuple[Scene, ...]
    notes: tuple[str, ...] = ()

    @property
    def name(self) -> str:
        """The mechanism's name."""
        return self.frames[0].result.name

    @property
    def answers(self) -> tuple[str, ...]:
        """DOF, pattern and mobility of each pose in one line (with the pose's label when there are several)."""
        out = []
        for k, f in enumerate(self.frames):
            r = f.result
            text = f"end effector {r.dof} DOF, pattern {r.pattern}; mobility {r.mobility} (Grübler–Kutzbach count {r.gruebler_kutzbach})"
            out.append(text if len(self.frames) == 1 else f"{f.label or f'pose {k + 1}'}: {text}")
        return tuple(out)

    @property
    def answer(self) -> str:
        """DOF, pattern and mobility of the first pose in one line (the page's header then shows the slider's pose)."""
        return self.answers[0]

    @property
    def header(self) -> list[str]:
        """The lines under the answer in the page's header, true of every pose (units, counts of patterns, notes...)."""
        return header_lines([f.result for f in self.frames], [f.label for f in self.frames]) + list(self.notes)

    @cached_property
    def figure_dict(self) -> dict[str, Any]:
        """The plotly figure as a JSON-ready dict (no plotly needed)."""
        return build_figure_dict([(s, f.result, f.label) for s, f in zip(self.scenes, self.frames)])

    @property
    def figure(self) -> Any:
        """The view as a :class:`plotly.graph_objects.Figure` (validated; needs plotly)."""
        require_plotly()
        import plotly.graph_objects as go

        return go.Figure(self.figure_dict)

    def to_html(self) -> str:
        """The self-contained page (plotly.js inline; nothing fetched from the network)."""
        # one pose: the page's header says it all; several poses keep the title the slider updates
        figure = self.figure_dict if len(self.frames) > 1 else build_figure_dict([(self.scenes[0], self.frames[0].result, self.frames[0].label)], titled=False)
        return page_html(figure, self.name, self.answers, self.header, [screws_table(s) for s in self.scenes])

    def write_html(self, path: str | Path) -> Path:
        """Write :meth:`to_html` to ``path``, whole or not at all (:func:`mobility.outputs.atomic_output`); returns the path.

        A :class:`MissingExtraError` without plotly; a :class:`RequestError` when ``path`` is not a file name or cannot be written.
        """
        path = written_file_name(path, "write_html")
        text = self.to_html()
        try:
            with atomic_output(path) as handle:  # the previous page intact until the new one is whole
                handle.write(text)
        except OSError as exc:
            raise RequestError(f"cannot write {path}: {exc.strerror or exc}") from None
        return path

    def text(self) -> str:
        """The text form: the text report of one pose, a line per pose for several."""
        if len(self.frames) == 1:
            return text_report(self.frames[0].result)
        lines = [self.name, *("  " + x for x in self.header)]
        for k, f in enumerate(self.frames):
            lines.append(f"  {f.label or k + 1}: {f.result.dof} DOF ({f.result.pattern}), mobility {f.result.mobility}, {margin_text(f.result)}")
        return "\n".join(lines)

    def _repr_mimebundle_(self, include: Any = None, exclude: Any = None) -> dict[str, Any]:
        """Jupyter: the figure as :func:`mobility.view.page.offline_mimebundle` gives it, the text report as plain text."""
        try:
            figure = self.figure
        except MissingExtraError as exc:
            return {"text/plain": f"{self.text()}\n({exc})"}
        bundle = offline_mimebundle(figure)
        bundle["text/plain"] = self.text()
        return bundle

    def __repr__(self) -> str:
        return f"<View of {self.name}: {counted(len(self.frames), 'pose')}>"


def mechanism_view(mechanism: Mechanism, result: Result | None = None, *, tol: Tolerance = DEFAULT_TOLERANCE) -> View:
    """The 3D view of ``mechanism`` at its pose with its end effector's freedoms and constraints.

    ``result``: its analysis at this pose (computed with ``tol`` when not given; a
    :class:`RequestError` when it is not a :class:`Result` of ``mechanism``).

    Examples
    --------
    >>> import mobility
    >>> mechanism_view(mobility.load("mechanisms/four_bar.yaml")).answer
    'end effector 1 DOF, pattern 1R; mobility 1 (Grübler–Kutzbach count -2)'
    """
    mechanism = require_mechanism(mechanism, "mechanism_view")
    tol = require_tolerance(tol, "mechanism_view")
    result = require_result_of(mechanism, result, "mechanism_view") if result is not None else analyze(mechanism, tol=tol)
    return poses_view([ViewFrame(mechanism, result)])


MAX_POSES = 200
"""The most poses one view holds (every pose is in the page; pick a subset of a large sweep)."""


def require_max_poses(value: object, caller: str) -> int:
    """``value`` as the ``max_poses`` of a view: an integer (not a bool) from 1 to :data:`MAX_POSES`; else a :class:`RequestError` naming ``caller``.

    Examples
    --------
    >>> require_max_poses(None, "sweep_view")
    Traceback (most recent call last):
    mobility.errors.RequestError: sweep_view: max_poses: expected an integer from 1 to 200 (poses a view holds), got None
    """
    return require_integer(value, f"an integer from 1 to {MAX_POSES} (poses a view holds)", caller=caller, argument="max_poses", low=1, high=MAX_POSES)


def poses_view(frames: Iterable[ViewFrame | tuple], *, max_poses: int = MAX_POSES, notes: Iterable[str] = ()) -> View:
    """A 3D view of several poses with a slider: each pose's freedoms, constraints, pattern and margin.

    Parameters
    ----------
    frames : iterable of ViewFrame or (Mechanism, Result, label)
        In slider order.
    max_poses : int
        Refuse more poses, from 1 to :data:`MAX_POSES` (each adds about 40 kB to the page).
    notes : iterable of str
        Further lines of the header, true of every pose.

    Raises
    ------
    RequestError
        For frames that are none, too many, or not a mechanism with its own result, or a bad argument.

    Examples
    --------
    >>> import mobility
    >>> m = mobility.load("mechanisms/four_bar.yaml")
    >>> poses = [m, *mobility.sample_poses(m, 2, step=0.2, seed=1)]
    >>> v = poses_view([(p, mobility.analyze(p), f"pose {k}") for k, p in enumerate(poses)])
    >>> len(v.frames), v.figure_dict["layout"]["sliders"][0]["steps"][2]["label"]
    (3, 'pose 2')
    """
    max_poses = require_max_poses(max_poses, "poses_view")
    notes = _notes(notes)
    try:
        given = None if isinstance(frames, (Mechanism, ViewFrame, str, bytes)) else iter(frames)
    except TypeError:  # not iterable
        given = None
    if given is None:
        hint = " (for one pose: [ViewFrame(...)], or mechanism_view)" if isinstance(frames, (Mechanism, ViewFrame)) else ""
        raise RequestError(caller="poses_view", argument="frames", expected="an iterable of ViewFrames or (mechanism, result, label) tuples", got=f"{type(frames).__name__}{hint}")
    out = []
    for k, f in enumerate(itertools.islice(given, max_poses + 1)):  # one more tells there are too many (an endless generator ends)
        if not isinstance(f, ViewFrame):
            if not (isinstance(f, tuple) and len(f) in (2, 3)):
                raise RequestError(argument=f"frame {k}", expected="a ViewFrame or a (mechanism, result, label) tuple", got=type(f).__name__)
            f = ViewFrame(*f)
        if not isinstance(f.mechanism, Mechanism) or not isinstance(f.result, Result):
            raise RequestError(argument=f"frame {k}", expected="a Mechanism and its Result", got=f"{type(f.mechanism).__name__} and {type(f.result).__name__}")
        require_result_of(f.mechanism, f.result, f"frame {k}")
        out.append(f)
    if not out:
        raise RequestError("a view needs at least one pose")
    if len(out) > max_poses:
        count = len(frames) if isinstance(frames, Sized) else f"{len(out)} or more"
        raise RequestError(f"{count} poses is more than a view holds (max_poses={max_poses}); show a subset, e.g. every k-th pose")
    # one drawing scale for every pose (1 for a mechanism of an everyday size), so that the poses share their axes
    drawing = drawing_scale(joint_screws(out[0].mechanism).normalisation.length)
    return View(tuple(out), tuple(build_scene(f.mechanism, f.result, drawing) for f in out), notes)


def _notes(notes: object) -> tuple[str, ...]:
    """The ``notes`` of :func:`poses_view`: an iterable of strings (not one string), else a :class:`RequestError`."""
    try:
        listed = None if isinstance(notes, (str, bytes)) else tuple(itertools.islice(notes, MAX_POSES + 1))  # type: ignore[call-overload]
    except TypeError:  # not iterable
        listed = None
    if listed is None or len(listed) > MAX_POSES or not all(isinstance(n, str) for n in listed):
        raise RequestError(caller="poses_view", argument="notes", expected="a list of lines (strings)", got=shown_argument(notes))
    return listed
