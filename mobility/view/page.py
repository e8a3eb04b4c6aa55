"""One self-contained HTML page holding the 3D view: it works offline.

The page embeds plotly.js itself (about 4.8 MB, no script, style sheet or
font fetched from the network, no MathJax) under a short header: the
mechanism's name, its DOF, pattern and mobility, the units, the explanation
of the Grübler–Kutzbach count and the warnings, and how to use the view.
With several poses the header's answer follows the slider: a short script
writes the answer of the pose shown.  :func:`figure_html` is the figure
alone, as offline, for a notebook's HTML output.

plotly is an optional extra (``pip install 'mechanism-mobility[view]'``);
:func:`require_plotly` says so in one line when it is missing.
"""

from __future__ import annotations

import html
import json
from typing import Any, Sequence

from ..errors import MissingExtraError
from .figure import ELEMENT_ID

__all__ = ["require_plotly", "page_html", "figure_html", "answer_script", "PLOTLY_CONFIG"]

PLOTLY_CONFIG = {"displaylogo": False, "responsive": True, "scrollZoom": True}
"""The plotly.js options of the view: no logo, fills its page, the wheel zooms."""

_HELP = (
    "Drag to rotate, scroll to zoom, right-drag (or shift-drag) to pan; hover a glyph for its numbers. "
    "Click a legend entry to hide or show it, a legend's title to switch its whole layer."
)

_STYLE = """
body { margin: 0; font-family: system-ui, -apple-system, "Segoe UI", Roboto, Helvetica, Arial, sans-serif; color: #263238; background: #fff; }
header { padding: 10px 16px 4px; border-bottom: 1px solid #eceff1; }
header h1 { font-size: 20px; margin: 0 0 4px; }
header p { margin: 2px 0; font-size: 14px; }
header .answer { font-size: 16px; }
header .warning { color: #b71c1c; }
header .help { color: #607d8b; font-size: 13px; }
"""


def require_plotly() -> Any:
    """Import :mod:`plotly.io`, or raise :class:`~mobility.errors.MissingExtraError` with the install line."""
    try:
        import plotly.io as pio
    except ImportError as exc:
        detail = "" if (exc.name or "plotly").split(".")[0] == "plotly" else f"missing module {exc.name!r}"
        raise MissingExtraError("the 3D view", "plotly", "view", detail) from None
    return pio


def figure_html(figure: dict[str, Any], *, div_id: str | None = None, post_script: Sequence[str] = ()) -> str:
    """The figure as an HTML fragment that fetches nothing: plotly.js inline, no MathJax, no CDN.

    Parameters
    ----------
    figure : dict
        From :func:`mobility.view.figure.figure_dict` (or a plotly figure's dict).
    div_id : str, optional
        The id of the figure's element (default: a new random one, so that
        several figures can share a notebook).
    post_script : sequence of str
        Scripts run once the figure is drawn (``{plot_id}`` is the element's id).
    """
    pio = require_plotly()
    return pio.to_html(figure, include_plotlyjs=True, include_mathjax=False, full_html=False, div_id=div_id, config=PLOTLY_CONFIG,
                       validate=False, default_height=f"{figure['layout'].get('height', 720)}px", default_width="100%",
                       post_script=list(post_script) or None)


def answer_script(answers: Sequence[str]) -> str:
    """The script that writes, in the header's answer, the answer of the pose the slider shows.

    ``answers[k]`` is the text of pose ``k`` (the order of the slider's
    steps).  The texts are written as JSON with every ``<``, ``>``, ``&``
    and brace escaped, so no text can end the script or take the place of
    ``{plot_id}``.

    Examples
    --------
    >>> print(answer_script(["a", "</script>"]))  # doctest: +NORMALIZE_WHITESPACE
    var gd = document.getElementById('{plot_id}'); var answers = ["a", "\\u003c/script\\u003e"];
    gd.on('plotly_sliderchange', function (e) { var k = e.slider.active;
    var p = document.querySelector('header .answer'); if (p && answers[k] !== undefined) { p.textContent = answers[k]; } });
    """
    text = json.dumps(list(answers), ensure_ascii=True)
    for char in "<>&{}":
        text = text.replace(char, f"\\u{ord(char):04x}")
    return (
        f"var gd = document.getElementById('{{plot_id}}'); var answers = {text};\n"
        "gd.on('plotly_sliderchange', function (e) { var k = e.slider.active;\n"
        "var p = document.querySelector('header .answer'); if (p && answers[k] !== undefined) { p.textContent = answers[k]; } });"
    )


def page_html(figure: dict[str, Any], title: str, answers: Sequence[str], lines: Sequence[str]) -> str:
    """The whole page: header, then the figure with plotly.js inline.

    Parameters
    ----------
    figure : dict
        From :func:`mobility.view.figure.figure_dict`.
    title : str
        The mechanism's name (the page's title and heading).
    answers : sequence of str
        DOF, pattern and mobility of each pose in one line, in the slider's
        order: the header shows the first, then the one of the pose the slider
        shows.
    lines : sequence of str
        Further header lines, true of every pose; those starting with
        ``warning:`` are shown in red.
    """
    scripts = [answer_script(answers)] if len(answers) > 1 else []
    body = figure_html(figure, div_id=ELEMENT_ID, post_script=scripts)
    paragraphs = "\n".join(
        f'<p class="{"warning" if line.startswith("warning:") else "detail"}">{html.escape(line)}</p>' for line in lines
    )
    return (
        "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
        f"<title>{html.escape(title)}</title>\n<style>{_STYLE}</style>\n</head>\n<body>\n"
        f"<header>\n<h1>{html.escape(title)}</h1>\n<p class=\"answer\">{html.escape(answers[0])}</p>\n{paragraphs}\n"
        f"<p class=\"help\">{html.escape(_HELP)}</p>\n</header>\n<main>\n{body}\n</main>\n</body>\n</html>\n"
    )
