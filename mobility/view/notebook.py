"""Jupyter shows a :class:`~mobility.core.result.Result` (and a sweep result) as its interactive 3D view.

``import mobility`` inside IPython calls :func:`register_display` (the core knows nothing of views); what a
notebook then shows, fetching nothing: docs/view.md, "In Python and Jupyter".  Nothing here imports plotly or
IPython until it is used.
"""

from __future__ import annotations

from typing import Any

from ..core.result import Result
from ..report.text import text_report
from .page import offline_mimebundle

__all__ = ["result_mimebundle", "sweep_mimebundle", "register_display", "offline_mimebundle", "NOTEBOOK_POSES"]

NOTEBOOK_POSES = 60
"""Poses of a sweep shown in a notebook's slider (each is analysed again to be drawn)."""


def result_mimebundle(result: Result, *, rich: bool = True) -> dict[str, Any]:
    """The display of ``result``: the view of its mechanism (``rich``) with the text report as plain text.

    A result that does not carry its mechanism is shown as text.

    Examples
    --------
    >>> import mobility
    >>> r = mobility.analyze(mobility.load("mechanisms/four_bar.yaml"))
    >>> bundle = result_mimebundle(r, rich=False)
    >>> list(bundle), bundle["text/plain"].splitlines()[1]
    (['text/plain'], '  end-effector DOF: 1   pattern: 1R')
    """
    mechanism = getattr(result.detail, "mechanism", None)
    if not rich or mechanism is None:
        return {"text/plain": text_report(result)}
    from .views import mechanism_view

    return mechanism_view(mechanism, result)._repr_mimebundle_()


def sweep_mimebundle(sweep: Any, *, rich: bool = True) -> dict[str, Any]:
    """The display of a sweep result: a slider through its poses (``rich``), its text summary as plain text."""
    from ..report.sweep import sweep_summary

    text = sweep_summary(sweep)
    if not rich:
        return {"text/plain": text}
    from .sweep import sweep_view

    bundle = sweep_view(sweep, max_poses=NOTEBOOK_POSES)._repr_mimebundle_()
    hint = bundle["text/plain"].splitlines()[-1] if len(bundle) == 1 else ""  # without plotly: the install line
    bundle["text/plain"] = f"{text}\n{hint}" if hint.startswith("(") else text
    return bundle


def register_display(shell: Any) -> None:
    """Make IPython ``shell`` display every :class:`Result` and sweep result as its view.

    Rich when the front end shows HTML, plain text in a terminal; the sweeps package is not imported for it.
    """
    formatter = shell.display_formatter
    rich = "text/html" in getattr(formatter, "active_types", ())
    formatter.mimebundle_formatter.for_type(Result, lambda r: result_mimebundle(r, rich=rich))
    formatter.mimebundle_formatter.for_type_by_name("mobility.sweeps.result", "SweepResult", lambda s: sweep_mimebundle(s, rich=rich))
