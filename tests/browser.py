"""Headless Chromium for the tests of the 3D view, driven by Playwright.

The browser is Debian's ``chromium``: ``.ci/run`` installs it, and so does the
suite itself when it runs as root on a machine without it; Playwright never
downloads one.  It starts with a new, empty profile and everything that
could reach the network switched off (the network is closed here, and a page
that works offline must not need it).  A missing browser or Playwright is a
failure, not a skip.

Run as a script, it makes the screenshots of the docs the same way the tests do, at 1400x900::

    python tests/browser.py mechanisms/3prs_tilted.yaml docs/img/view.png
    python tests/browser.py mechanisms/{3prs_tilted,3prs,delta,four_bar,bricard_orthogonal}.yaml docs/img
"""

from __future__ import annotations

import contextlib
import os
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path
from typing import Iterator

CHROMIUM_FLAGS = (
    "--headless",
    "--no-sandbox",
    "--disable-gpu",
    "--disable-background-networking",
    "--disable-component-update",
    "--disable-sync",
    "--no-first-run",
)

# The glyphs of the current pose as the page holds them: distinct keys of the visible traces, by layer.
GLYPHS_JS = """(id) => {
    const gd = document.getElementById(id);
    const out = {mechanism: new Set(), freedoms: new Set(), constraints: new Set()};
    for (const t of gd.data) {
        if (t.visible === true && t.meta) out[t.meta.layer].add(t.meta.key);
    }
    return {mechanism: [...out.mechanism], freedoms: [...out.freedoms], constraints: [...out.constraints]};
}"""


def chromium_path() -> str:
    """The Chromium executable: ``$MOBILITY_CHROMIUM``, else ``chromium`` on the PATH, else Debian's path."""
    return os.environ.get("MOBILITY_CHROMIUM") or shutil.which("chromium") or "/usr/bin/chromium"


def ensure_chromium() -> str:
    """The Chromium executable, installed from Debian's packages first when it is absent and we may.

    The suite installs the browser it drives: as root on a Debian-like machine
    (CI, a fresh container) ``apt-get install chromium`` runs once; elsewhere
    the error says what to install.  Never a skip.
    """
    exe = chromium_path()
    if Path(exe).is_file() or "MOBILITY_CHROMIUM" in os.environ:
        return exe
    if hasattr(os, "geteuid") and os.geteuid() == 0 and shutil.which("apt-get"):
        env = {**os.environ, "DEBIAN_FRONTEND": "noninteractive"}
        for command in (["apt-get", "update", "-qq"], ["apt-get", "install", "-y", "-qq", "chromium"]):
            subprocess.run(command, env=env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, check=False, timeout=900)
        exe = chromium_path()
    return exe


@contextlib.contextmanager
def browser_context(width: int = 1280, height: int = 900) -> Iterator:
    """A Playwright browser context of headless Chromium with a new empty profile; closed on exit.

    Raises
    ------
    RuntimeError
        When Playwright or Chromium cannot be found (the message says how to install them).
    """
    try:
        from playwright.sync_api import sync_playwright
    except ImportError as exc:
        raise RuntimeError(f"the browser tests need playwright (pip install -e '.[test]'): {exc}") from None
    exe = ensure_chromium()
    if not Path(exe).is_file():
        raise RuntimeError(f"the browser tests need Chromium at {exe}: apt-get install chromium (or set MOBILITY_CHROMIUM)")
    with tempfile.TemporaryDirectory(prefix="mobility-chromium-") as profile, sync_playwright() as p:
        context = p.chromium.launch_persistent_context(
            profile, executable_path=exe, headless=True, args=list(CHROMIUM_FLAGS),
            viewport={"width": width, "height": height}, device_scale_factor=1,
        )
        try:
            yield context
        finally:
            context.close()


class Tab:
    """One browser tab that opens pages of the view, keeping what each logged and every request it made.

    Pages are opened one after the other in the same tab: Chromium then
    keeps its compiled scripts and WebGL set-up, which makes each next page
    several times faster to show in software rendering.
    """

    def __init__(self, context, element_id: str = "mobility-view") -> None:
        self.page = context.new_page()
        self.console: list[tuple[str, str]] = []
        self.requests: list[str] = []
        self.page.on("console", lambda m: self.console.append((m.type, m.text)))
        self.page.on("pageerror", lambda e: self.console.append(("pageerror", str(e))))
        self.page.on("request", lambda r: self.requests.append(r.url))
        self.element_id = element_id

    def open(self, path: Path) -> "Tab":
        """Show the page at ``path`` and wait until plotly has drawn its 3D scene."""
        self.console.clear()
        self.requests.clear()
        self.page.goto(Path(path).resolve().as_uri(), wait_until="load")
        self.page.wait_for_function(
            "(id) => { const gd = document.getElementById(id); return gd && gd._fullData && gd.querySelector('canvas'); }",
            arg=self.element_id, timeout=30_000,
        )
        self.page.wait_for_timeout(300)  # let the first WebGL frame be drawn
        return self

    def errors(self) -> list[tuple[str, str]]:
        return [(kind, text) for kind, text in self.console if kind in ("error", "pageerror")]

    def glyphs(self) -> dict[str, list[str]]:
        return self.page.evaluate(GLYPHS_JS, self.element_id)

    def wait_for_glyphs(self, layer: str, count: int, timeout: float = 10_000) -> None:
        """Wait until the current pose shows ``count`` glyphs of ``layer`` (a click on a legend acts after the double-click delay)."""
        self.page.wait_for_function(
            f"([id, layer, count]) => ({GLYPHS_JS})(id)[layer].length === count", arg=[self.element_id, layer, count], timeout=timeout
        )
        self.page.wait_for_timeout(200)  # and the WebGL frame is drawn

    def scene_box(self) -> dict[str, float]:
        """The box of the 3D scene on the page (inside the figure, without header, legends and slider)."""
        return self.page.evaluate(
            """(id) => { const gd = document.getElementById(id); const s = gd._fullLayout.scene._scene;
                const r = gd.getBoundingClientRect(); const d = gd._fullLayout.scene.domain, w = gd._fullLayout.width, h = gd._fullLayout.height;
                const m = gd._fullLayout.margin; const pw = w - m.l - m.r, ph = h - m.t - m.b;
                return {x: r.left + window.scrollX + m.l + d.x[0] * pw, y: r.top + window.scrollY + m.t + (1 - d.y[1]) * ph,
                        width: (d.x[1] - d.x[0]) * pw, height: (d.y[1] - d.y[0]) * ph}; }""",
            self.element_id,
        )

    def label_boxes(self) -> list[dict]:
        """The labels of the freedoms and constraints shown: each one's text and its box on the page (the SVG of its annotation)."""
        return self.page.evaluate(
            """() => [...document.querySelectorAll('.annotation-text-g')].filter(e => e.getBoundingClientRect().width > 0).map(e => {
                const r = e.getBoundingClientRect(); return {text: e.textContent, x: r.left, y: r.top, width: r.width, height: r.height}; })"""
        )

    def show_only(self, layers: tuple[str, ...], labels: bool) -> None:
        """Show only the traces of ``layers`` (and the labels, or not), then wait for the WebGL frame: for pictures of parts of the view."""
        self.page.evaluate(
            """([id, layers, labels]) => { const gd = document.getElementById(id);
                const visible = gd.data.map(t => t.meta && t.meta.frame === 0 && layers.includes(t.meta.layer));
                Plotly.restyle(gd, {visible: visible});
                const notes = gd.layout.scene.annotations || [];
                const update = {}; notes.forEach((a, i) => { update['scene.annotations[' + i + '].visible'] = labels; });
                return Plotly.relayout(gd, update); }""",
            [self.element_id, list(layers), labels],
        )
        self.page.wait_for_timeout(400)

    def screenshot(self, path: Path | None = None, *, scene_only: bool = False) -> bytes:
        clip = self.scene_box() if scene_only else None
        return self.page.screenshot(path=str(path) if path else None, clip=clip, full_page=clip is None)

SHOT_SIZE = (1400, 900)
"""The window of the docs' screenshots of the view (docs/img/view-*.png), pixels."""


def small_png(png: bytes, path: Path) -> Path:
    """Write a screenshot as a small PNG (256 colours: the view's flat colours and text stay sharp)."""
    import io

    from PIL import Image

    image = Image.open(io.BytesIO(png)).convert("RGB").quantize(colors=256, method=Image.Quantize.FASTOCTREE)
    image.save(path, optimize=True)
    return path


def main(argv: list[str]) -> int:
    """``python tests/browser.py MECHANISM.yaml... OUT``: screenshots of the views of mechanism files at 1400x900.

    With one file and ``OUT`` a ``.png``, that file; otherwise ``OUT`` is a
    folder and each view is written there as ``view-<stem>.png``.
    """
    import mobility
    from mobility.view import mechanism_view

    sources, out = [Path(a) for a in argv[:-1]], Path(argv[-1])
    with tempfile.TemporaryDirectory() as tmp, browser_context(*SHOT_SIZE) as context:
        tab = Tab(context)
        for source in sources:
            page_path = mechanism_view(mobility.load(source)).write_html(Path(tmp) / "view.html")
            tab.open(page_path)
            if tab.errors():
                print(f"{source}: console errors: {tab.errors()}", file=sys.stderr)
                return 1
            target = out if out.suffix == ".png" else out / f"view-{source.stem}.png"
            small_png(tab.page.screenshot(), target)
            print(f"wrote {target}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
