"""One self-contained HTML page holding the 3D view: it works offline.

plotly.js is embedded (about 4.8 MB; nothing fetched, no MathJax) under a header giving the mechanism's
name, its answer (following the slider), units, warnings and how to use the view; :func:`figure_html`
is the figure alone, for a notebook.
"""

from __future__ import annotations

import html
import json
from typing import Any, Sequence

from ..errors import MissingExtraError
from .figure import ELEMENT_ID

__all__ = ["require_plotly", "page_html", "figure_html", "offline_mimebundle", "answer_script", "screws_table", "LABELS_SCRIPT", "PLOTLY_CONFIG"]

PLOTLY_CONFIG = {"displaylogo": False, "responsive": True, "scrollZoom": True}
"""The plotly.js options of the view: no logo, fills its page, the wheel zooms."""

_HELP = ("Drag to rotate, scroll to zoom, right-drag (or shift-drag) to pan; hover a glyph for its numbers. "
         "Click a legend entry to hide or show it, a legend's title to switch its whole layer.")

_STYLE = """
body { margin: 0; font-family: system-ui, -apple-system, "Segoe UI", Roboto, Helvetica, Arial, sans-serif; color: #263238; background: #fff; }
header { padding: 10px 16px 4px; border-bottom: 1px solid #eceff1; }
header h1 { font-size: 20px; margin: 0 0 4px; }
header p { margin: 2px 0; font-size: 14px; }
header .answer { font-size: 16px; }
header .warning { color: #b71c1c; }
header .help { color: #607d8b; font-size: 13px; }
main { display: flex; align-items: flex-start; }
main > .figure { flex: 1 1 auto; min-width: 0; }
aside { order: 2; flex: 0 0 340px; box-sizing: border-box; max-height: 720px; overflow: auto; padding: 8px 14px; border-left: 1px solid #eceff1; font-size: 13px; }
aside h2 { font-size: 14px; margin: 10px 0 4px; }
aside table { border-collapse: collapse; width: 100%; }
aside td { padding: 3px 4px; vertical-align: top; border-bottom: 1px solid #eceff1; }
aside td.key { font-weight: bold; white-space: nowrap; }
aside .numbers { font-family: ui-monospace, "DejaVu Sans Mono", Menlo, Consolas, monospace; font-size: 12px; }
"""

LABELS_SCRIPT = ("var gd = document.getElementById('{plot_id}');\n"
                 "gd.on('plotly_restyle', function () { var shown = {}, update = {}, notes = (gd.layout.scene && gd.layout.scene.annotations) || [];\n"
                 "gd.data.forEach(function (t) { if (t.meta && t.visible === true) { shown[t.meta.key] = true; } });\n"
                 "notes.forEach(function (a, i) { var now = a.visible !== false, want = shown[a.name] === true;\n"
                 "if (now !== want) { update['scene.annotations[' + i + '].visible'] = want; } });\n"
                 "if (Object.keys(update).length) { Plotly.relayout(gd, update); } });")
"""The script that hides the label of a glyph hidden from its legend, and shows it again with it."""


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

    ``div_id`` defaults to a random one (several figures share a notebook); ``post_script``
    runs once the figure is drawn (``{plot_id}``: the element's id), after :data:`LABELS_SCRIPT`.
    """
    pio = require_plotly()
    return pio.to_html(figure, include_plotlyjs=True, include_mathjax=False, full_html=False, div_id=div_id, config=PLOTLY_CONFIG,
                       validate=False, default_height=f"{figure['layout'].get('height', 720)}px", default_width="100%",
                       post_script=[LABELS_SCRIPT, *post_script])


def answer_script(answers: Sequence[str]) -> str:
    """The script that writes, in the header's answer, the answer of the pose the slider shows, and shows its table of screws.

    The texts are written as JSON with ``<``, ``>``, ``&`` and braces escaped,
    so that no text can end the script or stand for ``{plot_id}``.

    Examples
    --------
    >>> print(answer_script(["a", "</script>"]))  # doctest: +NORMALIZE_WHITESPACE
    var gd = document.getElementById('{plot_id}'); var answers = ["a", "\\u003c/script\\u003e"];
    gd.on('plotly_sliderchange', function (e) { var k = e.slider.active;
    var p = document.querySelector('header .answer'); if (p && answers[k] !== undefined) { p.textContent = answers[k]; }
    document.querySelectorAll('aside .screws').forEach(function (s, i) { s.hidden = i !== k; }); });
    """
    text = json.dumps(list(answers), ensure_ascii=True)
    for char in "<>&{}":
        text = text.replace(char, f"\\u{ord(char):04x}")
    return (f"var gd = document.getElementById('{{plot_id}}'); var answers = {text};\n"
            "gd.on('plotly_sliderchange', function (e) { var k = e.slider.active;\n"
            "var p = document.querySelector('header .answer'); if (p && answers[k] !== undefined) { p.textContent = answers[k]; }\n"
            "document.querySelectorAll('aside .screws').forEach(function (s, i) { s.hidden = i !== k; }); });")


def screws_table(scene: Any) -> str:
    """The freedoms and constraints of a scene as an HTML table: each one's key in its colour, its kind and its numbers (the hover text's).

    Examples
    --------
    >>> import mobility
    >>> from mobility.view.scene import build_scene
    >>> m = mobility.load("mechanisms/four_bar.yaml")
    >>> text = screws_table(build_scene(m, mobility.analyze(m)))
    >>> text.count("<tr"), "R1" in text, "axis [0, 0, 1]" in text
    (6, True, True)
    """
    parts = []
    for layer, heading in (("freedoms", "freedoms of the end effector"), ("constraints", "constraint wrenches on it")):
        glyphs = scene.layer(layer)
        rows = []
        for g in glyphs:
            lines = [html.escape(html.unescape(x)) for x in g.hover.split("<br>")]
            kind = lines[0].split(" ", 1)[1] if " " in lines[0] else ""
            rows.append(f'<tr data-key="{html.escape(g.key)}"><td class="key" style="color: {html.escape(g.color)}">{html.escape(g.key)}</td>'
                        f'<td>{kind}<div class="numbers">{"<br>".join(lines[1:])}</div></td></tr>')
        body = "\n".join(rows) if rows else '<tr><td colspan="2">none</td></tr>'
        parts.append(f"<h2>{heading} ({len(glyphs)})</h2>\n<table>\n{body}\n</table>")
    return "\n".join(parts)


def page_html(figure: dict[str, Any], title: str, answers: Sequence[str], lines: Sequence[str], tables: Sequence[str] = ()) -> str:
    """The whole page: header, then the figure with plotly.js inline, and beside it the table of its screws.

    ``answers``: each pose's DOF, pattern and mobility in one line, and ``tables``: each pose's :func:`screws_table`
    (none: no table), in the slider's order; ``lines``: further header lines, true of every pose (``warning:`` ones in red).
    """
    body = figure_html(figure, div_id=ELEMENT_ID, post_script=[answer_script(answers)] if len(answers) > 1 else [])
    paragraphs = "\n".join(
        f'<p class="{"warning" if line.startswith("warning:") else "detail"}">{html.escape(line)}</p>' for line in lines
    )
    aside = "".join(f'<section class="screws"{"" if k == 0 else " hidden"}>\n{t}\n</section>\n' for k, t in enumerate(tables))
    return (
        "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
        f"<title>{html.escape(title)}</title>\n<style>{_STYLE}</style>\n</head>\n<body>\n"
        f"<header>\n<h1>{html.escape(title)}</h1>\n<p class=\"answer\">{html.escape(answers[0])}</p>\n{paragraphs}\n"
        f"<p class=\"help\">{html.escape(_HELP)}</p>\n</header>\n<main>\n"
        # the table first: the figure, drawn as the page is read, then takes the width left beside it
        + (f"<aside>\n{aside}</aside>\n" if tables else "") + f"<div class=\"figure\">\n{body}\n</div>\n</main>\n</body>\n</html>\n"
    )


PLOTLY_JSON = "application/vnd.plotly.v1+json"
"""The mime type of plotly's JSON form (what plotly picks in a Jupyter kernel)."""


def offline_mimebundle(figure: Any) -> dict[str, Any]:
    """The forms of ``figure`` (mime type -> data) that plotly's default renderers name, none of them fetching anything.

    HTML renderers (``notebook``, ``iframe``...) give way to :func:`~mobility.view.page.figure_html`, which also goes along
    with the JSON form; other renderers give their own form, those opening a browser none.
    """
    import plotly.io as pio

    fig_dict = figure.to_plotly_json()
    bundle: dict[str, Any] = {}
    for name in filter(None, (pio.renderers.default or "").split("+")):
        renderer = pio.renderers[name]
        if any(c.__name__ in ("HtmlRenderer", "IFrameRenderer") for c in type(renderer).__mro__):  # its HTML would load MathJax from a CDN
            bundle["text/html"] = figure_html(fig_dict)
        elif hasattr(renderer, "to_mimebundle"):
            bundle.update(renderer.to_mimebundle(fig_dict))
    if PLOTLY_JSON in bundle and "text/html" not in bundle:
        # only a front end with plotly's extension draws the JSON: the HTML goes along for nbconvert, GitHub and other viewers
        bundle["text/html"] = figure_html(fig_dict)
    return bundle
