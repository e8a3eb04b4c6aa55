"""The interactive 3D view: scene, figure, page, command line, notebook display, and the page in a real browser.

The browser tests drive Debian's headless Chromium through Playwright
(``tests/browser.py``); a missing browser fails them.  They check what a
person sees: the page loads with no console error and fetches nothing from
the network, the 3D canvas is not blank, it holds as many freedom glyphs as
the result has DOF and as many constraint glyphs as constraint wrenches, and
a layer's title switches the layer off (its colour leaves the picture).
"""

from __future__ import annotations

import dataclasses
import io
import json
import re
import sys
from pathlib import Path
from types import SimpleNamespace

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import mobility
from mobility.cli import main
from mobility.core.loop_closure import loop_closure
from mobility.errors import MissingExtraError, RequestError
from mobility.report.text import text_report
from mobility.view import LAYERS, ViewFrame, build_scene, mechanism_view, poses_view, sweep_view
from mobility.view.figure import LEGENDS
from mobility.view.notebook import register_display, result_mimebundle, sweep_mimebundle

from browser import Tab, browser_context

ROOT = Path(__file__).resolve().parent.parent
MECHANISMS = ROOT / "mechanisms"
ALL_FILES = sorted(MECHANISMS.glob("*.yaml"))
BROWSER_FILES = ["3prs_tilted.yaml", "agile_eye.yaml", "four_bar.yaml"]  # a page costs seconds in software WebGL
NUMBER = r"-?\d+(?:\.\d+)?(?:e[-+]?\d+)?"


def _load(name: str):
    m = mobility.load(MECHANISMS / name)
    return m, mobility.analyze(m)


def _vector(text: str, word: str) -> np.ndarray:
    found = re.search(rf"{word} \[({NUMBER}), ({NUMBER}), ({NUMBER})\]", text)
    assert found, f"no '{word} [..]' in {text!r}"
    return np.array([float(x) for x in found.groups()])


def _pitch(text: str, word: str) -> float:
    found = re.search(rf"{word} ({NUMBER})", text)
    return float(found.group(1)) if found else 0.0


def _screws_from_hover(scene, layer: str) -> np.ndarray:
    """The screws a person reads in the hover text of a layer (rows [w; v] or [f; m]), as written."""
    rows = []
    for g in scene.layer(layer):
        if g.kind in ("translation", "couple"):
            rows.append(np.r_[np.zeros(3), _vector(g.hover, "direction" if g.kind == "translation" else "about")])
        else:
            d = _vector(g.hover, "axis" if layer == "freedoms" else "along")
            p = _vector(g.hover, "through")
            h = _pitch(g.hover, "pitch") if layer == "freedoms" else _pitch(g.hover, "couple pitch")
            rows.append(np.r_[d, np.cross(p, d) + h * d])
    return np.array(rows).reshape(-1, 6)


# ---------------------------------------------------------------------------
# the scene: as many glyphs as freedoms and constraints, each where its screw is


@pytest.mark.parametrize("path", ALL_FILES, ids=lambda p: p.stem)
def test_scene_has_one_glyph_per_freedom_and_constraint(path):
    m = mobility.load(path)
    r = mobility.analyze(m)
    scene = build_scene(m, r)
    freedoms, constraints = scene.layer("freedoms"), scene.layer("constraints")
    assert len(freedoms) == r.dof == loop_closure(m).end_effector_twists.shape[1]  # the second route agrees
    assert len(constraints) == 6 - r.dof
    assert [g.key for g in freedoms] == [f"T{i + 1}" for i in range(r.translation_count)] + [f"R{i + 1}" for i in range(len(r.rotations))]
    assert {g.layer for g in scene.glyphs} <= set(LAYERS)
    assert len({g.key for g in scene.glyphs}) == len(scene.glyphs)
    assert np.all(scene.lower <= scene.upper) and scene.size > 0


@pytest.mark.parametrize("name", ["3prs_tilted.yaml", "agile_eye.yaml", "four_bar.yaml", "3upu_singular.yaml", "metrom.yaml"])
def test_the_numbers_a_person_reads_are_reciprocal_screws(name):
    """Parsed back from the hover text (6 digits), the freedoms and constraints shown are reciprocal, each of full rank."""
    m, r = _load(name)
    scene = build_scene(m, r)
    twists, wrenches = _screws_from_hover(scene, "freedoms"), _screws_from_hover(scene, "constraints")
    L = r.length_scale
    scale = np.diag([1, 1, 1, 1 / L, 1 / L, 1 / L])  # lengths over the mechanism's size: products become unitless
    t, w = twists @ scale, wrenches @ scale
    t, w = t / np.linalg.norm(t, axis=1, keepdims=True), w / np.linalg.norm(w, axis=1, keepdims=True)
    reciprocal = t[:, :3] @ w[:, 3:].T + t[:, 3:] @ w[:, :3].T
    assert np.max(np.abs(reciprocal), initial=0.0) < 1e-4
    # of full rank: together they are the twist system and its whole reciprocal
    assert (np.linalg.matrix_rank(t, tol=1e-4) if len(t) else 0) == r.dof
    assert (np.linalg.matrix_rank(w, tol=1e-4) if len(w) else 0) == 6 - r.dof


def test_glyphs_are_drawn_where_their_screws_are():
    m, r = _load("3prs_tilted.yaml")
    scene = build_scene(m, r)
    by_key = {g.key: g for g in scene.glyphs}
    for i, a in enumerate(r.rotations):
        g = by_key[f"R{i + 1}"]
        axis_points = g.path[:15]  # the first piece: the axis line itself
        off_axis = np.cross(axis_points - a.point, a.axis)
        assert np.max(np.linalg.norm(off_axis, axis=1)) < 1e-9 * scene.size
        assert abs(abs(g.direction @ a.axis) - 1) < 1e-12
    for i, f in enumerate(r.forces):
        g = by_key[f"W{len(r.couples) + i + 1}"]
        tip = g.mesh.vertices[0]  # the arrowhead's tip lies on the force line
        assert np.linalg.norm(np.cross(tip - f.point, f.axis)) < 1e-9 * scene.size
    for i, t in enumerate(r.translations):
        g = by_key[f"T{i + 1}"]
        shaft = g.path[-1] - g.path[0]
        assert np.allclose(shaft / np.linalg.norm(shaft), t)
        assert np.allclose(g.path[0], scene.centre)


@settings(max_examples=15, deadline=None)
@given(scale=st.floats(1e-3, 1e3), shift=st.tuples(*[st.floats(-10.0, 10.0)] * 3))
def test_a_scaled_and_moved_mechanism_looks_the_same(scale, shift):
    """Glyph sizes are fractions of the scene: metres or millimetres, here or there, the same picture."""
    m, r = _load("3prs_tilted.yaml")
    shift = np.array(shift)
    moved = m.replace(joints=tuple(
        dataclasses.replace(j, point=None if j.point is None else tuple(scale * np.asarray(j.point) + scale * shift))
        for j in m.world_joints), frames=())
    a, b = build_scene(m, r), build_scene(moved, mobility.analyze(moved))
    assert [g.key for g in a.glyphs] == [g.key for g in b.glyphs]
    for ga, gb in zip(a.glyphs, b.glyphs):
        expected = scale * (ga.extent() + shift)
        assert np.allclose(gb.extent(), expected, rtol=0, atol=1e-6 * scale * a.size), ga.key


# ---------------------------------------------------------------------------
# the figure, the page


def test_figure_traces_carry_layer_key_and_frame_and_plotly_accepts_them():
    import plotly.graph_objects as go

    m, r = _load("3prs_tilted.yaml")
    fig = mechanism_view(m, r).figure_dict
    json.dumps(fig)  # JSON-ready as it is
    go.Figure(fig)  # plotly validates every attribute
    keys = {layer: {t["meta"]["key"] for t in fig["data"] if t["meta"]["layer"] == layer} for layer in LAYERS}
    assert keys["freedoms"] == {"T1", "R1", "R2"} and keys["constraints"] == {"C1", "W2", "W3"}
    for t in fig["data"]:
        assert t["legend"] == LEGENDS[t["meta"]["layer"]] and t["legendgroup"] == t["meta"]["key"]
    assert sum(t["showlegend"] for t in fig["data"]) == len({t["meta"]["key"] for t in fig["data"]})  # one entry per glyph
    hover = {t["meta"]["key"]: t["hovertext"] for t in fig["data"] if t["type"] == "mesh3d"}
    assert "pitch -0.921859 mm/rad" in hover["R2"] and "couple pitch 0.921859 mm" in hover["W3"]


def test_slider_shows_one_pose_at_a_time():
    frames = _parallelogram_frames()
    view = poses_view(frames)
    fig = view.figure_dict
    steps = fig["layout"]["sliders"][0]["steps"]
    assert [s["label"] for s in steps] == [f.label for f in frames]
    for k, (step, frame) in enumerate(zip(steps, frames)):
        shown = [t for t, v in zip(fig["data"], step["args"][0]["visible"]) if v]
        assert {t["meta"]["frame"] for t in shown} == {k}
        assert len({t["meta"]["key"] for t in shown if t["meta"]["layer"] == "freedoms"}) == frame.result.dof
        assert frame.result.pattern in step["args"][1]["title.text"]
    assert [t["visible"] for t in fig["data"]] == [t["meta"]["frame"] == 0 for t in fig["data"]]


def test_a_sweep_is_shown_pose_by_pose_with_its_own_answers():
    m = mobility.load(MECHANISMS / "parallelogram.yaml")
    sweep = mobility.sweep(m, vary={"O1": (-90, 150, 9)})  # every 30 deg: folded at -60 and 120
    view = sweep_view(sweep)
    assert [f.label for f in view.frames] == [f"O1={v:g} deg" for v in range(-90, 151, 30)]
    # the view analyses each pose again: its answers agree with the batched sweep, pose by pose
    assert [f.result.dof for f in view.frames] == sweep.dof.tolist() == [1, 2, 1, 1, 1, 1, 1, 2, 1]
    for scene, frame in zip(view.scenes, view.frames):
        assert len(scene.layer("freedoms")) == frame.result.dof
    thinned = sweep_view(mobility.sweep(m, vary={"O1": (-180, 180, 37)}), max_poses=5)
    assert len(thinned.frames) == 5 and {"O1=-60 deg", "O1=120 deg"} <= {f.label for f in thinned.frames}
    with pytest.raises(RequestError, match="expected a sweep result"):
        sweep_view(m)


def test_poses_view_refuses_what_is_not_a_pose():
    m, r = _load("four_bar.yaml")
    with pytest.raises(RequestError, match="at least one pose"):
        poses_view([])
    with pytest.raises(RequestError, match="frame 1: expected a Mechanism and its Result"):
        poses_view([(m, r, "a"), (r, m, "b")])
    with pytest.raises(RequestError, match="frame 0: expected a ViewFrame"):
        poses_view(["four_bar.yaml"])
    with pytest.raises(RequestError, match="3 poses is more than a view holds"):
        poses_view([(m, r, "a")] * 3, max_poses=2)


def test_page_is_self_contained_and_states_the_answer(tmp_path):
    m, r = _load("3prs_tilted.yaml")
    page = mechanism_view(m, r).write_html(tmp_path / "v.html").read_text()
    assert not re.search(r"""<(script|link|img|iframe)[^>]+(src|href)=["']?(https?:)?//""", page)  # nothing fetched
    assert "@import" not in page and "<link" not in page
    assert "end effector 3 DOF, pattern 1T2R; mobility 3 (Grübler–Kutzbach count 3)" in page
    assert "<title>3-PRS parallel head (Sprint Z3), tilted pose</title>" in page
    assert len(page.encode()) < 6_000_000


def test_page_header_escapes_the_name(tmp_path):
    m, r = _load("four_bar.yaml")
    m = m.replace(name="<script>alert(1)</script> & co")
    page = mechanism_view(m).to_html()
    assert "<h1>&lt;script&gt;alert(1)&lt;/script&gt; &amp; co</h1>" in page


def test_names_are_shown_as_written_in_hover_texts_titles_and_slider_labels():
    # Plotly reads tags in its texts: a joint "gr<b>o</b>und&" was shown with a bold o, "ü<br>x" on two lines
    m, _ = _load("four_bar.yaml")
    renamed = {"A": "gr<b>o</b>und&", "B": "ü<br>x"}
    m = m.replace(name="<i>bar</i>", joints=tuple(dataclasses.replace(j, name=renamed.get(j.name, j.name)) for j in m.joints),
                  end_effector=m.end_effector)
    r = mobility.analyze(m)
    figure = poses_view([ViewFrame(m, r, "<b>first</b>"), ViewFrame(m, r, "second & last")]).figure_dict
    hovers = [h for t in figure["data"] for h in (t.get("hovertext") if isinstance(t.get("hovertext"), list) else [t.get("hovertext") or ""])]
    joined = "\n".join(hovers)
    assert "gr&lt;b&gt;o&lt;/b&gt;und&amp;: R revolute" in joined and "ü&lt;br&gt;x: R revolute" in joined
    assert "<b>" not in joined and "ü<br>x" not in joined  # our own line breaks stay: '<br>' between lines
    title = figure["layout"]["title"]["text"]
    assert title.startswith("&lt;i&gt;bar&lt;/i&gt; — &lt;b&gt;first&lt;/b&gt;: end effector") and "<i>" not in title
    assert [step["label"] for step in figure["layout"]["sliders"][0]["steps"]] == ["&lt;b&gt;first&lt;/b&gt;", "second &amp; last"]


def test_without_plotly_the_view_says_what_to_install(monkeypatch):
    for name in [n for n in sys.modules if n == "plotly" or n.startswith("plotly.")]:
        monkeypatch.delitem(sys.modules, name)
    monkeypatch.setitem(sys.modules, "plotly", None)  # import plotly now raises ImportError
    m, r = _load("four_bar.yaml")
    view = mechanism_view(m, r)
    with pytest.raises(MissingExtraError) as err:
        view.to_html()
    assert str(err.value) == "the 3D view needs plotly, which is not installed: pip install 'mechanism-mobility[view]'"
    bundle = view._repr_mimebundle_()  # a notebook falls back to text, with the hint
    assert list(bundle) == ["text/plain"] and "pattern: 1R" in bundle["text/plain"] and "mechanism-mobility[view]" in bundle["text/plain"]
    err_out = io.StringIO()
    monkeypatch.setattr(sys, "stderr", err_out)
    assert main(["view", str(MECHANISMS / "four_bar.yaml"), "-o", "x.html"]) == 2
    assert err_out.getvalue() == "mobility: the 3D view needs plotly, which is not installed: pip install 'mechanism-mobility[view]'\n"


# ---------------------------------------------------------------------------
# the command line


def test_cli_writes_the_page(tmp_path, capsys):
    out = tmp_path / "view.html"
    assert main(["view", str(MECHANISMS / "agile_eye.yaml"), "-o", str(out)]) == 0
    said = capsys.readouterr().out
    assert said.startswith(f"wrote {out}: ") and "3 DOF (3R)" in said
    assert out.read_text().count('"layer":"freedoms"') >= 3


def test_cli_samples_poses_with_a_slider(tmp_path, capsys):
    out = tmp_path / "view.html"
    assert main(["view", str(MECHANISMS / "four_bar.yaml"), "-o", str(out), "--samples", "2", "--seed", "3"]) == 0
    assert "3 poses" in capsys.readouterr().out
    page = out.read_text()
    assert '"label":"sampled pose 2"' in page and "use the slider" in page


def test_cli_shows_a_sweep_with_a_slider(tmp_path, capsys):
    out = tmp_path / "sweep.html"
    assert main(["view", str(MECHANISMS / "parallelogram.yaml"), "-o", str(out), "--vary", "O1=0:120:3"]) == 0
    assert "3 poses" in capsys.readouterr().out
    page = out.read_text()
    assert '"label":"O1=120 deg"' in page and "(1T1R)" in page


@pytest.mark.parametrize(
    ("args", "message"),
    [
        (["four_bar.yaml", "-o", "v.html", "--vary", "A=0:1"], "--vary 'A=0:1': expected NAME=START:STOP:COUNT"),
        (["four_bar.yaml", "-o", "view.png"], "view.png: expected a page name ending in .html or .htm (in any case)"),
        (["four_bar.yaml", "-o", "view.html.txt"], "view.html.txt: expected a page name ending in .html or .htm (in any case)"),
        (["missing.yaml", "-o", "v.html"], "missing.yaml"),
        (["four_bar.yaml", "-o", "v.html", "--samples", "-1"], "--samples must lie in [0, 1000]"),
        (["four_bar.yaml", "-o", "no/such/dir/v.html"], "cannot write"),
        (["four_bar.yaml", "-o", "v.html", "--tol", "0.5"], "--tol must lie in"),
    ],
)
def test_cli_bad_input_is_one_line_and_exit_2(args, message, tmp_path, monkeypatch, capsys):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "four_bar.yaml").write_text((MECHANISMS / "four_bar.yaml").read_text())
    assert main(["view", *args]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and message in err and "Traceback" not in err


def test_cli_bounds_a_sweep_by_max_poses_as_sweep_does(tmp_path, capsys):
    from mobility.cli import build_parser
    from mobility.sweeps import DEFAULT_MAX_POSES

    out = tmp_path / "v.html"
    base = ["view", str(MECHANISMS / "four_bar.yaml"), "-o", str(out), "--vary", "A=0:10:100"]
    assert main(base + ["--max-poses", "50"]) == 2  # was: no such option, every grid drawn at any size
    err = capsys.readouterr().err
    assert err == "mobility: --vary A=0:10:100: 100 values, more than --max-poses 50; raise --max-poses or use fewer points\n"
    assert not out.exists()
    assert main(base + ["--max-poses", "0"]) == 2
    assert capsys.readouterr().err == "mobility: --max-poses must be at least 1, got 0\n"
    assert main(base + ["--max-poses", "100"]) == 0 and out.exists()
    defaults = [build_parser([c]).parse_args([c, "f.yaml", "-o", "v.html", "--vary", "A=0:1:2"]).max_poses for c in ("view", "sweep")]
    assert defaults == [DEFAULT_MAX_POSES, DEFAULT_MAX_POSES]


@pytest.mark.parametrize("name", ["v.htm", "v.HTML", "v.Htm"])
def test_cli_takes_the_page_names_its_message_names(name, tmp_path, capsys):
    out = tmp_path / name
    assert main(["view", str(MECHANISMS / "four_bar.yaml"), "-o", str(out)]) == 0
    assert capsys.readouterr().out.startswith(f"wrote {out}: ") and out.read_text().startswith("<!DOCTYPE html>")


def test_cli_planar_5r_sweep_says_which_poses_are_not_drawn(tmp_path, capsys):
    """The page draws the assembled poses only, and says how many of the grid's poses are missing and why."""
    vary = ["A1=-90:90:5", "A2=-90:90:5"]
    sweep = mobility.sweep(mobility.load(MECHANISMS / "planar_5r.yaml"), vary)
    assembled = int(sweep.assembled.sum())
    assert sweep.size == 25 and 0 < assembled < 25
    out = tmp_path / "five_bar.html"
    assert main(["view", str(MECHANISMS / "planar_5r.yaml"), "-o", str(out), "--vary", vary[0], "--vary", vary[1]]) == 0
    said = capsys.readouterr()
    assert said.out.endswith(f", {assembled} poses\n") and said.err == ""  # stdout and stderr as before
    page = out.read_text()
    assert page.count('"label":"A1=') == assembled
    assert (f"<p class=\"detail\">{assembled} of the sweep&#x27;s 25 poses drawn: {25 - assembled} not assembled "
            "(no closed pose reached there)</p>") in page
    # a thinned sweep says so too; a sweep drawn whole says nothing
    m = mobility.load(MECHANISMS / "parallelogram.yaml")
    thinned = sweep_view(mobility.sweep(m, vary={"O1": (-180, 180, 37)}), max_poses=5)
    assert thinned.notes == ("5 of the sweep's 37 poses drawn: 32 assembled poses left out (evenly spaced ones drawn, every singular one kept)",)
    assert thinned.notes[0] in thinned.text()
    assert sweep_view(mobility.sweep(m, vary={"O1": (0, 120, 3)})).notes == ()


def test_cli_takes_samples_or_a_sweep_not_both(capsys):
    with pytest.raises(SystemExit) as stop:
        main(["view", "four_bar.yaml", "-o", "v.html", "--vary", "A=0:10:2", "--samples", "2"])
    assert stop.value.code == 2
    assert capsys.readouterr().err == "mobility view: error: argument --samples: not allowed with argument --vary (see mobility view --help)\n"


@pytest.mark.parametrize("samples", [200, 1000])
def test_cli_refuses_more_samples_than_a_view_holds_before_any_work(tmp_path, capsys, monkeypatch, samples):
    # it sampled the poses, then failed naming a Python keyword (max_poses=200) that the command line has not
    import mobility.cli.view as command

    monkeypatch.setattr(command, "sampled_poses", lambda *a: pytest.fail("the poses were sampled"))
    target = tmp_path / "v.html"
    assert main(["view", str(ROOT / "mechanisms" / "four_bar.yaml"), "-o", str(target), "--samples", str(samples)]) == 2
    assert capsys.readouterr().err == f"mobility: --samples {samples}: a view shows at most 200 poses, the file's and 199 sampled; ask for fewer\n"
    assert not target.exists()


def test_cli_bad_file_names_file_line_and_key(write_yaml, tmp_path, capsys):
    path = write_yaml("name: x\nground: g\nend_effector: e\njoints:\n  - {name: A, type: R, links: [g, e], axis: [0, 0], point: [0, 0, 0]}\n")
    assert main(["view", str(path), "-o", str(tmp_path / "v.html")]) == 2
    err = capsys.readouterr().err.strip()
    assert err.startswith(f"mobility: {path}:5: joints[0].axis") and "\n" not in err


# ---------------------------------------------------------------------------
# Jupyter


def test_a_result_shows_itself_as_the_view_in_a_notebook(monkeypatch):
    import plotly.io as pio
    from IPython.core.formatters import DisplayFormatter

    monkeypatch.setattr(pio.renderers, "default", "plotly_mimetype")  # what plotly picks in a Jupyter kernel
    formatter = DisplayFormatter()
    register_display(SimpleNamespace(display_formatter=formatter))
    m, r = _load("3prs_tilted.yaml")
    data, _ = formatter.format(r)
    fig = data["application/vnd.plotly.v1+json"]
    freedoms = {t["meta"]["key"] for t in fig["data"] if t["meta"]["layer"] == "freedoms"}
    assert len(freedoms) == r.dof
    assert data["text/plain"] == text_report(r)
    # a terminal shows the text report
    terminal = DisplayFormatter(active_types=["text/plain"])
    register_display(SimpleNamespace(display_formatter=terminal))
    assert terminal.format(r)[0] == {"text/plain": text_report(r)}


def test_a_sweep_shows_itself_as_a_slider_in_a_notebook(monkeypatch):
    import plotly.io as pio
    from IPython.core.formatters import DisplayFormatter

    from mobility.report.sweep import sweep_summary

    monkeypatch.setattr(pio.renderers, "default", "plotly_mimetype")
    formatter = DisplayFormatter()
    register_display(SimpleNamespace(display_formatter=formatter))
    sweep = mobility.sweep(mobility.load(MECHANISMS / "parallelogram.yaml"), vary={"O1": (0, 120, 3)})
    data, _ = formatter.format(sweep)
    steps = data["application/vnd.plotly.v1+json"]["layout"]["sliders"][0]["steps"]
    assert [s["label"] for s in steps] == ["O1=0 deg", "O1=60 deg", "O1=120 deg"]
    assert data["text/plain"] == sweep_summary(sweep) == sweep_mimebundle(sweep, rich=False)["text/plain"]


def _addresses(page: str) -> list[str]:
    """The src and href attributes of every element of an HTML text (script bodies are text, not elements)."""
    from html.parser import HTMLParser

    found: list[str] = []

    class Reader(HTMLParser):
        def handle_starttag(self, tag, attrs):
            found.extend(v or "" for k, v in attrs if k in ("src", "href"))

    Reader().feed(page)
    return found


@pytest.mark.parametrize("renderers", ["plotly_mimetype+notebook", "notebook", "notebook_connected", "colab", "iframe", "plotly_mimetype"])
def test_the_notebook_display_fetches_nothing(renderers, monkeypatch, tmp_path):
    """Whatever plotly's renderers ask for, the HTML of a result's or a sweep's display loads nothing from the network."""
    import plotly.io as pio

    monkeypatch.chdir(tmp_path)  # plotly's iframe renderer would write files here
    monkeypatch.setattr(pio.renderers, "default", renderers)
    m, r = _load("four_bar.yaml")
    sweep = mobility.sweep(mobility.load(MECHANISMS / "parallelogram.yaml"), vary={"O1": (0, 120, 3)})
    for bundle in (result_mimebundle(r), sweep_mimebundle(sweep)):
        if renderers == "plotly_mimetype":  # what plotly picks in a kernel: the HTML goes along, for nbconvert and viewers
            assert set(bundle) == {"application/vnd.plotly.v1+json", "text/html", "text/plain"}
        page = bundle["text/html"]
        assert "<script" in page and [a for a in _addresses(page) if re.match(r"\s*(https?:)?//", a, re.IGNORECASE)] == []
        assert 'import "http' not in page and "mathjax/" not in page.lower()
        assert "plotly.js v" in page[:2000] and '"layer":"freedoms"' in page  # plotly.js and the figure are inline
        assert ("application/vnd.plotly.v1+json" in bundle) == renderers.startswith("plotly_mimetype")
    assert list(tmp_path.iterdir()) == []  # and no file was written


def test_a_result_without_its_mechanism_is_shown_as_text():
    m, r = _load("four_bar.yaml")
    class WithoutMechanism:  # the analysis's details, less the mechanism
        def __getattr__(self, name):
            if name == "mechanism":
                raise AttributeError(name)
            return getattr(r.detail, name)

    bare = mobility.Result(**{f: getattr(r, f) for f in r.__dataclass_fields__ if f != "detail"}, detail=WithoutMechanism())
    assert result_mimebundle(bare) == {"text/plain": text_report(r)}


def test_a_notebook_kernel_displays_results_with_plotly():
    import nbclient
    import nbformat

    nb = nbformat.v4.new_notebook(cells=[nbformat.v4.new_code_cell(
        "import mobility\nmobility.analyze(mobility.load('mechanisms/agile_eye.yaml'))")])
    nbclient.NotebookClient(nb, timeout=120, kernel_name="python3", resources={"metadata": {"path": str(ROOT)}}).execute()
    (out,) = nb.cells[0].outputs
    fig = out["data"]["application/vnd.plotly.v1+json"]
    layers = [t["meta"]["layer"] for t in fig["data"]]
    assert "freedoms" in layers and "pattern: 3R" in out["data"]["text/plain"]
    assert len({t["meta"]["key"] for t in fig["data"] if t["meta"]["layer"] == "constraints"}) == 3


# ---------------------------------------------------------------------------
# in a real browser


def _parallelogram_frames() -> list[ViewFrame]:
    m = mobility.load(MECHANISMS / "parallelogram.yaml")
    poses = [m, *mobility.sample_poses(m, 2, step=0.3, seed=2), mobility.load(MECHANISMS / "parallelogram_change_point.yaml")]
    labels = ["as in the file", "sampled 1", "sampled 2", "change point"]
    return [ViewFrame(p, mobility.analyze(p), lab) for p, lab in zip(poses, labels)]


@pytest.fixture(scope="module")
def tab():
    """One tab of headless Chromium for every page of this module."""
    try:
        with browser_context() as context:
            yield Tab(context)
    except RuntimeError as exc:  # no browser: a failure, never a skip
        pytest.fail(str(exc))


def _rgb(hex_colour: str) -> np.ndarray:
    return np.array([int(hex_colour[i:i + 2], 16) for i in (1, 3, 5)], dtype=float)


def _pixels(png: bytes) -> np.ndarray:
    from PIL import Image

    return np.asarray(Image.open(io.BytesIO(png)).convert("RGB"), dtype=float)


def _share_of(image: np.ndarray, colour: str, within: float = 40.0) -> float:
    return float(np.mean(np.linalg.norm(image - _rgb(colour), axis=2) < within))


def _layer_colours(scene, layer: str) -> set[str]:
    return {g.color for g in scene.layer(layer)}


@pytest.mark.parametrize("name", BROWSER_FILES)
def test_page_in_the_browser_shows_one_glyph_per_freedom_and_constraint(tab, name, tmp_path):
    m, r = _load(name)
    view = mechanism_view(m, r)
    page = tab.open(view.write_html(tmp_path / "view.html"))
    assert page.errors() == []
    assert [u for u in page.requests if not u.startswith("file:")] == []  # works offline
    header = page.page.inner_text("header")
    assert f"end effector {r.dof} DOF, pattern {r.pattern}; mobility {r.mobility}" in header
    glyphs = page.glyphs()
    assert len(glyphs["freedoms"]) == r.dof
    assert len(glyphs["constraints"]) == 6 - r.dof
    before = _pixels(page.screenshot(scene_only=True))
    assert np.mean(np.linalg.norm(before - 255.0, axis=2) > 30) > 0.005  # not blank
    assert max(_share_of(before, c) for c in _layer_colours(view.scenes[0], "freedoms")) > 2e-4
    # the constraints layer's title switches it off: its glyphs leave the figure, its colours the picture
    colours = _layer_colours(view.scenes[0], "constraints")
    shown = {c: _share_of(before, c, 25.0) for c in colours}
    assert max(shown.values()) > 2e-4
    page.page.locator("rect.legend3titletoggle").click()
    page.wait_for_glyphs("constraints", 0)
    assert len(page.glyphs()["freedoms"]) == r.dof
    after = _pixels(page.screenshot(scene_only=True))
    for c in colours:
        assert _share_of(after, c, 25.0) < 0.2 * shown[c] + 1e-6, c
    page.page.locator("rect.legend3titletoggle").click()  # and back on
    page.wait_for_glyphs("constraints", 6 - r.dof)


def test_the_slider_walks_through_the_poses_in_the_browser(tab, tmp_path):
    frames = _parallelogram_frames()
    assert [f.result.dof for f in frames] == [1, 1, 1, 2]  # the change point gains a freedom
    page = tab.open(poses_view(frames).write_html(tmp_path / "poses.html"))
    assert page.errors() == []
    assert len(page.glyphs()["freedoms"]) == 1
    rail = page.page.locator(".slider-rail-rect").bounding_box()
    page.page.mouse.click(rail["x"] + rail["width"] - 1, rail["y"] + rail["height"] / 2)  # the last pose
    page.wait_for_glyphs("freedoms", 2)
    assert len(page.glyphs()["constraints"]) == 4
    title = page.page.evaluate("(id) => document.getElementById(id)._fullLayout.title.text", page.element_id)
    assert "change point" in title and "(1T1R)" in title and "margin" in title
    page.page.mouse.click(rail["x"] + 1, rail["y"] + rail["height"] / 2)  # back to the first
    page.wait_for_glyphs("freedoms", 1)
    assert len(page.glyphs()["constraints"]) == 5


def _slider_to(page, k: int, count: int) -> int:
    """Click the slider's rail where step ``k`` of ``count`` sits; returns the step the page then shows."""
    rail = page.page.locator(".slider-rail-rect").bounding_box()
    x = rail["x"] + 1 + (rail["width"] - 2) * k / (count - 1)
    page.page.mouse.click(x, rail["y"] + rail["height"] / 2)
    page.page.wait_for_function(f"(id) => document.getElementById(id)._fullLayout.sliders[0].active === {k}", arg=page.element_id, timeout=10_000)
    page.page.wait_for_timeout(200)
    return page.page.evaluate("(id) => document.getElementById(id)._fullLayout.sliders[0].active", page.element_id)


def _title(page) -> str:
    return page.page.evaluate("(id) => document.getElementById(id)._fullLayout.title.text", page.element_id)


def test_the_header_follows_the_slider_in_the_browser(tab, tmp_path, capsys):
    """The page of the README's fold: the header's answer is the pose's the slider shows, as the title is."""
    out = tmp_path / "fold.html"
    assert main(["view", str(MECHANISMS / "parallelogram.yaml"), "-o", str(out), "--vary", "O1=-90:150:9"]) == 0
    capsys.readouterr()
    page = tab.open(out)
    assert page.errors() == [] and [u for u in page.requests if not u.startswith("file:")] == []
    answer = lambda: page.page.inner_text("header .answer")  # noqa: E731
    first = "O1=-90 deg: end effector 1 DOF, pattern 1T; mobility 1 (Grübler–Kutzbach count -2)"
    assert answer() == first
    assert _slider_to(page, 7, 9) == 7
    assert "O1=120 deg" in _title(page) and "(1T1R), mobility 2" in _title(page)
    assert answer() == "O1=120 deg: end effector 2 DOF, pattern 1T1R; mobility 2 (Grübler–Kutzbach count -2)"
    assert len(page.glyphs()["freedoms"]) == 2
    header = page.page.inner_text("header")
    assert "9 poses; patterns: 1T × 7, 1T1R × 2" in header and "O1=-90" not in header  # the rest is true of every pose
    assert _slider_to(page, 0, 9) == 0
    assert answer() == first and "O1=-90 deg" in _title(page)
    assert page.errors() == []


def test_the_header_writes_any_label_as_text_in_the_browser(tab, tmp_path):
    """Labels are the page's text, never its markup or script, in the header the slider rewrites."""
    m, r = _load("four_bar.yaml")
    labels = ["<b>first</b>", "</script><script>document.title='x'</script>", "{plot_id} & \\u003c 'q' \"r\""]
    view = poses_view([ViewFrame(m, r, label) for label in labels])
    page = tab.open(view.write_html(tmp_path / "labels.html"))
    assert page.errors() == []
    assert page.page.inner_text("header .answer") == view.answers[0] == f"{labels[0]}: end effector 1 DOF, pattern 1R; mobility 1 (Grübler–Kutzbach count -2)"
    for k in (2, 1):
        assert _slider_to(page, k, 3) == k
        assert page.page.inner_text("header .answer") == view.answers[k]
    assert page.page.title() == "planar four-bar" and page.page.locator("header b").count() == 0


def test_the_notebook_html_works_offline_in_the_browser(tab, tmp_path, monkeypatch):
    import plotly.io as pio

    monkeypatch.setattr(pio.renderers, "default", "notebook_connected")  # plotly's own would fetch plotly.js and MathJax
    m, r = _load("agile_eye.yaml")
    fragment = result_mimebundle(r)["text/html"]
    element = re.search(r'<div id="([^"]+)" class="plotly-graph-div"', fragment).group(1)
    path = tmp_path / "cell.html"
    path.write_text(f"<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"></head><body>{fragment}</body></html>\n", encoding="utf-8")
    cell = Tab(tab.page.context, element_id=element).open(path)
    try:
        assert cell.errors() == []
        assert [u for u in cell.requests if not u.startswith("file:")] == []
        assert len(cell.glyphs()["freedoms"]) == r.dof == 3 and len(cell.glyphs()["constraints"]) == 3
    finally:
        cell.page.close()


# ---------------------------------------------------------------------------
# legible at first sight: measured in the page as drawn, at the docs' window of 1400x900

LEGIBLE_FILES = ["3prs_tilted.yaml", "3prs.yaml", "delta.yaml", "four_bar.yaml", "bricard_orthogonal.yaml"]


def _page_pixels(page) -> np.ndarray:
    return _pixels(page.page.screenshot())


def _inside(box: dict, mask: np.ndarray) -> int:
    """How many pixels of ``mask`` lie in ``box`` (page pixels)."""
    x0, y0 = max(int(box["x"]), 0), max(int(box["y"]), 0)
    x1, y1 = int(np.ceil(box["x"] + box["width"])), int(np.ceil(box["y"] + box["height"]))
    return int(np.count_nonzero(mask[y0:y1, x0:x1]))


@pytest.fixture(scope="module")
def wide_tab(tab):
    """A second tab of the same browser, in the window of the docs' screenshots."""
    from browser import SHOT_SIZE

    wide = Tab(tab.page.context)
    wide.page.set_viewport_size({"width": SHOT_SIZE[0], "height": SHOT_SIZE[1]})
    yield wide
    wide.page.close()


@pytest.mark.parametrize("name", LEGIBLE_FILES)
def test_labels_do_not_collide_and_the_mechanism_fills_the_view(wide_tab, name, tmp_path):
    """Each freedom's and constraint's label is in the page, clear of the other labels, of the axis ticks and of the links.

    The boxes of the labels are read from the page (the SVG the browser
    drew); the tick labels and the links are pictures of the scene with only
    the axes, then only the mechanism, shown: their ink in a label's box is
    a collision.  And the box of the mechanism with its glyphs covers much
    of the figure (it covered about a fifth of it).
    """
    m, r = _load(name)
    page = wide_tab.open(mechanism_view(m, r).write_html(tmp_path / "view.html"))
    assert page.errors() == []
    boxes = page.label_boxes()
    expected = sorted(f"{g.key}" for g in build_scene(m, r).glyphs if g.layer != "mechanism")
    assert sorted(b["text"].split()[0] for b in boxes) == expected, "a label per freedom and constraint, in the page"
    for a, b in ((a, b) for i, a in enumerate(boxes) for b in boxes[i + 1:]):
        apart_x = max(a["x"], b["x"]) - min(a["x"] + a["width"], b["x"] + b["width"])
        apart_y = max(a["y"], b["y"]) - min(a["y"] + a["height"], b["y"] + b["height"])
        assert max(apart_x, apart_y) >= 0, f"labels {a['text']!r} and {b['text']!r} overlap"
    everything = _page_pixels(page)
    page.show_only((), labels=False)
    axes = _page_pixels(page)
    ticks = np.mean(axes, axis=2) < 160  # the tick labels and axis titles: the dark ink of the bare axes
    assert np.count_nonzero(ticks) > 500  # there are ticks to collide with
    for b in boxes:
        assert _inside(b, ticks) == 0, f"label {b['text']!r} is on the axis ticks"
    page.show_only(("mechanism",), labels=False)
    links = np.linalg.norm(_page_pixels(page) - axes, axis=2) > 120  # the links' lines (their translucent plates are fainter)
    for b in boxes:
        covered = _inside(b, links) / (b["width"] * b["height"])
        assert covered < 0.02, f"label {b['text']!r} lies on the links ({covered:.1%} of its box)"
    # the mechanism and its glyphs fill the figure: the box of what they add to the bare axes covers much of it (legends included)
    drawn = np.argwhere(np.linalg.norm(everything - axes, axis=2) > 60)
    figure = page.page.locator(f"#{page.element_id}").bounding_box()
    scene = page.scene_box()
    inside = drawn[(drawn[:, 1] >= scene["x"]) & (drawn[:, 1] < scene["x"] + scene["width"]) & (drawn[:, 0] >= scene["y"]) & (drawn[:, 0] < scene["y"] + scene["height"])]
    height = (inside[:, 0].max() - inside[:, 0].min()) / figure["height"]
    width = (inside[:, 1].max() - inside[:, 1].min()) / figure["width"]
    assert height * width > 0.35, f"the mechanism's box covers {height * width:.0%} of the figure ({height:.0%} of its height, {width:.0%} of its width)"


def test_a_label_follows_its_glyph_off_and_on(tab, tmp_path):
    """A glyph hidden from its legend takes its label with it; shown again, the label comes back."""
    m, r = _load("3prs_tilted.yaml")
    page = tab.open(mechanism_view(m, r).write_html(tmp_path / "view.html"))
    shown = lambda: sorted(b["text"].split()[0] for b in page.label_boxes())  # noqa: E731
    assert shown() == ["C1", "R1", "R2", "T1", "W2", "W3"]
    page.page.locator("rect.legend3titletoggle").click()
    page.wait_for_glyphs("constraints", 0)
    page.page.wait_for_function("() => document.querySelectorAll('.annotation-text-g').length === 3", timeout=10_000)
    assert shown() == ["R1", "R2", "T1"]
    page.page.locator("rect.legend3titletoggle").click()
    page.wait_for_glyphs("constraints", 3)
    page.page.wait_for_function("() => document.querySelectorAll('.annotation-text-g').length === 6", timeout=10_000)
    assert shown() == ["C1", "R1", "R2", "T1", "W2", "W3"]


def test_the_page_lists_the_screws_beside_the_plot(tab, tmp_path):
    """Beside the plot, a table of every freedom and constraint with its numbers, as the hover text gives them."""
    m, r = _load("3prs_tilted.yaml")
    page = tab.open(mechanism_view(m, r).write_html(tmp_path / "view.html"))
    rows = page.page.locator("aside tr[data-key]")
    assert rows.all_inner_texts() and [row.get_attribute("data-key") for row in rows.all()] == ["T1", "R1", "R2", "C1", "W2", "W3"]
    text = page.page.inner_text("aside")
    assert "pitch -0.921859 mm/rad" in text and "couple pitch 0.921859 mm" in text and "direction [0, 0, 1]" in text
    aside = page.page.locator("aside").bounding_box()
    plot = page.scene_box()
    assert aside["x"] >= plot["x"] + plot["width"] - 1  # beside the plot, not over it
    assert aside["y"] < plot["y"] + plot["height"] / 2  # at its height, not under it


def test_a_notebook_exported_to_html_shows_the_view_offline(tab, tmp_path):
    """``jupyter nbconvert --to html`` of a notebook that displays a Result carries the interactive view, drawn with nothing fetched."""
    import nbclient
    import nbformat
    from nbconvert import HTMLExporter

    nb = nbformat.v4.new_notebook(cells=[nbformat.v4.new_code_cell(
        "import mobility\nmobility.analyze(mobility.load('mechanisms/3prs_tilted.yaml'))")])
    nbclient.NotebookClient(nb, timeout=120, kernel_name="python3", resources={"metadata": {"path": str(ROOT)}}).execute()
    # nbconvert's own page template loads require.js and MathJax from a CDN; these two options (documented in docs/view.md) leave them out
    exported, _ = HTMLExporter(require_js_url="", mathjax_url="").from_notebook_node(nb)
    assert [a for a in _addresses(exported) if re.match(r"\s*(https?:)?//", a, re.IGNORECASE)] == []
    default, _ = HTMLExporter().from_notebook_node(nb)  # with nbconvert's defaults, only its template's two scripts are remote
    assert sorted(re.sub(r"^https://cdnjs.cloudflare.com/ajax/libs/(\w+).*", r"\1", a) for a in _addresses(default) if "//" in a) == ["mathjax", "require"]
    path = tmp_path / "notebook.html"
    path.write_text(exported, encoding="utf-8")
    element = re.search(r'id="([^"]+)"', re.search(r'<div [^>]*class="plotly-graph-div"[^>]*>', exported).group(0)).group(1)
    cell = Tab(tab.page.context, element_id=element).open(path)
    try:
        assert cell.errors() == []
        assert [u for u in cell.requests if not u.startswith("file:")] == []  # nothing left the file
        assert len(cell.glyphs()["freedoms"]) == 3 and len(cell.glyphs()["constraints"]) == 3
        assert len(cell.label_boxes()) == 6
        box = cell.page.locator(f'[id="{element}"]').bounding_box()  # a uuid may start with a digit: not a CSS id
        picture = _pixels(cell.page.screenshot(clip=box))
        assert np.mean(np.linalg.norm(picture - 255.0, axis=2) > 30) > 0.005  # not blank
        assert _share_of(picture, "#1565c0") > 2e-4  # the rotations' blue is drawn
    finally:
        cell.page.close()
