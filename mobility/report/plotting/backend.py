"""matplotlib, optional: import it on first use, build figures without pyplot, save them.

Missing, it is a :class:`~mobility.errors.PlottingUnavailableError`.  Figures are built without
:mod:`matplotlib.pyplot` (no global state); one left as a notebook cell's value shows itself as PNG.
"""

from __future__ import annotations

import functools
import io
import os
import re
import warnings
from contextlib import contextmanager
from pathlib import Path
from typing import TYPE_CHECKING, Any, Iterator

from ...core.validation import require_integer, require_real
from ...errors import PlotFormatError, PlottingUnavailableError, RequestError, counted, shown_argument
from ...outputs import atomic_output

if TYPE_CHECKING:  # pragma: no cover
    from matplotlib.figure import Figure

__all__ = ["FORMATS", "DPI_RANGE", "FIGSIZE_RANGE", "require_matplotlib", "new_figure", "require_figsize", "written_file_name", "picture_path", "save_figure"]

FORMATS = (".png", ".svg", ".pdf")
"""File types :func:`save_figure` writes (by suffix)."""

DPI_RANGE = (20, 600)
"""The resolutions :func:`save_figure` takes (dots per inch), as ``mobility plot --dpi``."""

FIGSIZE_RANGE = (1.0, 30.0)
"""The width and the height of a figure (inches) the pictures take: 30 inches at 600 dpi is 18,000 pixels a side."""


def require_matplotlib() -> Any:
    """Import matplotlib (and the 3D toolkit) or raise :class:`~mobility.errors.PlottingUnavailableError`."""
    try:
        import matplotlib
        import matplotlib.figure  # noqa: F401
        from mpl_toolkits.mplot3d import Axes3D  # noqa: F401  (registers the 3d projection)
    except ImportError as exc:
        missing = exc.name or ""
        raise PlottingUnavailableError("" if missing.split(".")[0] == "matplotlib" else f"missing module {missing!r}") from None
    return matplotlib


@functools.cache
def _figure_class() -> type:
    """A :class:`matplotlib.figure.Figure` that shows itself in Jupyter without pyplot's display hook (made on first use)."""
    from matplotlib.figure import Figure

    class MobilityFigure(Figure):
        """A figure of :mod:`mobility.report.plotting`; displays itself as PNG in Jupyter.

        Its texts are drawn as written (a name such as ``$_$`` is not TeX); only tick numbers keep mathtext.
        """

        def draw(self, renderer: Any) -> None:
            _literal_texts(self)
            super().draw(renderer)

        def _repr_png_(self) -> bytes:
            buf = io.BytesIO()
            with glyphs_summarised():
                self.savefig(buf, format="png", dpi=90, facecolor="white")
            return buf.getvalue()

    return MobilityFigure


def _literal_texts(fig: Any) -> None:
    """Turn off mathtext for every text of ``fig`` but the tick labels (names are user data, not TeX)."""
    from matplotlib.text import Text

    ticks: set[int] = set()
    for ax in fig.axes:
        for axis in (ax.xaxis, ax.yaxis, getattr(ax, "zaxis", None)):
            if axis is None:
                continue
            for tick in axis.get_major_ticks() + axis.get_minor_ticks():
                ticks.update((id(tick.label1), id(tick.label2)))
            ticks.add(id(axis.get_offset_text()))
    for text in fig.findobj(Text):
        if id(text) not in ticks:
            text.set_parse_math(False)


def new_figure(figsize: tuple[float, float], **options: Any) -> "Figure":
    """An empty figure of ``figsize`` inches, ``options`` going to :class:`matplotlib.figure.Figure` (after :func:`require_matplotlib`)."""
    return _figure_class()(figsize=figsize, **options)


def require_figsize(value: object, caller: str) -> tuple[float, float] | None:
    """``value`` as the ``figsize`` of a picture: None (the picture's own size), or a width and a height in :data:`FIGSIZE_RANGE` inches; else a :class:`RequestError` naming ``caller``.

    Examples
    --------
    >>> import numpy as np
    >>> require_figsize(np.array([8, 6]), "plot_graph")
    (8.0, 6.0)
    >>> require_figsize(5, "plot_mechanism")
    Traceback (most recent call last):
    mobility.errors.RequestError: plot_mechanism: figsize: expected None or (width, height) in inches, each from 1 to 30, got 5
    """
    if value is None:
        return None
    try:
        size = None if isinstance(value, (str, bytes)) else [require_real(x, "") for x in value]  # type: ignore[attr-defined]
    except (TypeError, RequestError):  # not iterable, not numbers
        size = None
    low, high = FIGSIZE_RANGE
    if size is None or len(size) != 2 or not all(low <= x <= high for x in size):
        raise RequestError(caller=caller, argument="figsize", expected=f"None or (width, height) in inches, each from {low:g} to {high:g}", got=shown_argument(value))
    return (float(size[0]), float(size[1]))


def written_file_name(path: object, what: str) -> Path:
    """``path`` as the :class:`~pathlib.Path` of a file to write when it names one as text (``str`` or ``os.PathLike``, no NUL), else a :class:`RequestError` naming ``what``.

    Examples
    --------
    >>> written_file_name(b"view.html", "write_html")
    Traceback (most recent call last):
    mobility.errors.RequestError: write_html: expected a file name (str or Path), got bytes
    """
    try:
        name = os.fspath(path) if isinstance(path, (str, os.PathLike)) else None
    except TypeError:  # an __fspath__ that returns neither str nor bytes
        name = None
    if not isinstance(name, str):
        raise RequestError(caller=what, expected="a file name (str or Path)", got=type(path).__name__)
    if "\x00" in name:
        raise RequestError(caller=what, expected="a file name without a NUL character")
    return Path(name)


def picture_path(path: str | Path, what: str = "") -> Path:
    """``path`` as a :class:`~pathlib.Path`, once its suffix names a type :func:`save_figure` writes (else a :class:`~mobility.errors.PlotFormatError`).

    A command line calls it before any work, so that a bad name fails at once; ``what`` is written before the path in the message.

    Examples
    --------
    >>> picture_path("four_bar.SVG").name
    'four_bar.SVG'
    >>> picture_path("out.gif", "--plot ")
    Traceback (most recent call last):
    ...
    mobility.errors.PlotFormatError: --plot out.gif: cannot tell the picture type; expected a name ending in .png, .svg, .pdf
    """
    p = written_file_name(path, what.strip() or "picture_path")
    if p.suffix.lower() not in FORMATS:
        raise PlotFormatError(f"{what}{path}: cannot tell the picture type; expected a name ending in {', '.join(FORMATS)}")
    return p


_MISSING_GLYPH = re.compile(r"Glyph (\d+) .*missing from (?:current )?font")


@contextmanager
def glyphs_summarised() -> Iterator[None]:
    """Around a drawing: matplotlib's warnings of characters its font lacks (drawn as boxes) become one naming them all; others pass through."""
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        yield
    missing = []
    for w in caught:
        found = _MISSING_GLYPH.search(str(w.message))
        if found:
            missing.append(chr(int(found[1])))
        else:
            warnings.warn_explicit(w.message, w.category, w.filename, w.lineno)
    if missing:
        shown = "".join(dict.fromkeys(missing))
        warnings.warn(f"the picture's font has no glyph for {counted(len(shown), 'character')} of the names ({shown}): drawn as boxes", UserWarning, stacklevel=3)


def save_figure(fig: "Figure", path: str | Path, *, dpi: int = 150) -> Path:
    """Write ``fig`` to ``path`` as PNG, SVG or PDF (by suffix) on a white background, whole or not at all; returns the path.

    A failure or an interrupt leaves a picture already at ``path`` as it was (:func:`mobility.outputs.atomic_output`).
    ``dpi``: an integer in :data:`DPI_RANGE`; a bad argument is a :class:`RequestError`, another suffix a :class:`PlotFormatError`.
    """
    if not callable(getattr(fig, "savefig", None)):
        raise RequestError(caller="save_figure", expected="a matplotlib Figure", got=type(fig).__name__)
    p = picture_path(written_file_name(path, "save_figure: path"))
    low, high = DPI_RANGE
    dots = require_integer(dpi, f"an integer from {low} to {high} (dots per inch)", caller="save_figure", argument="dpi", low=low, high=high)
    with glyphs_summarised(), atomic_output(p, binary=True) as handle:  # the previous picture intact until the new one is whole
        fig.savefig(handle, format=p.suffix[1:].lower(), dpi=dots, facecolor="white")
    return p
