"""One self-contained HTML page holding the 3D view: it works offline.

The page embeds plotly.js itself (about 4.8 MB, no script, style sheet or
font fetched from the network) under a short header: the mechanism's name,
its DOF, pattern and mobility, the units, the explanation of the
Grübler–Kutzbach count and the warnings, and how to use the view.

plotly is an optional extra (``pip install 'mobility[view]'``);
:func:`require_plotly` says so in one line when it is missing.
"""

from __future__ import annotations

import html
from typing import Any, Sequence

from ..errors import MissingExtraError
from .figure import ELEMENT_ID

__all__ = ["require_plotly", "page_html", "PLOTLY_CONFIG"]

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


def page_html(figure: dict[str, Any], title: str, answer: str, lines: Sequence[str]) -> str:
    """The whole page: header, then the figure with plotly.js inline.

    Parameters
    ----------
    figure : dict
        From :func:`mobility.view.figure.figure_dict`.
    title : str
        The mechanism's name (the page's title and heading).
    answer : str
        DOF, pattern and mobility in one line.
    lines : sequence of str
        Further header lines; those starting with ``warning:`` are shown in red.
    """
    pio = require_plotly()
    body = pio.to_html(figure, include_plotlyjs=True, full_html=False, div_id=ELEMENT_ID, config=PLOTLY_CONFIG,
                       validate=False, default_height=f"{figure['layout'].get('height', 720)}px", default_width="100%")
    paragraphs = "\n".join(
        f'<p class="{"warning" if line.startswith("warning:") else "detail"}">{html.escape(line)}</p>' for line in lines
    )
    return (
        "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
        f"<title>{html.escape(title)}</title>\n<style>{_STYLE}</style>\n</head>\n<body>\n"
        f"<header>\n<h1>{html.escape(title)}</h1>\n<p class=\"answer\">{html.escape(answer)}</p>\n{paragraphs}\n"
        f"<p class=\"help\">{html.escape(_HELP)}</p>\n</header>\n<main>\n{body}\n</main>\n</body>\n</html>\n"
    )
