"""Every notebook in ``notebooks/`` runs top to bottom and shows pictures (so none can rot).

The notebooks are executed together, each in its own kernel, concurrently
(nbclient's asynchronous API), which keeps the wall time near that of the
slowest one.  A notebook fails the test when a cell raises or when it draws
no picture.
"""

from __future__ import annotations

import asyncio
from pathlib import Path

import ipykernel  # noqa: F401  (the notebooks' kernel and pictures: the test extra installs them; a missing one fails, never skips)
import matplotlib  # noqa: F401
import nbclient
import nbformat

NOTEBOOKS = sorted((Path(__file__).resolve().parent.parent / "notebooks").glob("*.ipynb"))


async def _run(path: Path):
    nb = nbformat.read(path, as_version=4)
    client = nbclient.NotebookClient(nb, timeout=120, kernel_name="python3", resources={"metadata": {"path": str(path.parent)}})
    try:
        await client.async_execute()
    except Exception as exc:  # noqa: BLE001 - reported per notebook below
        return path, nb, exc
    return path, nb, None


def _images(nb) -> int:
    return sum(
        "image/png" in out.get("data", {})
        for cell in nb.cells
        if cell.cell_type == "code"
        for out in cell.get("outputs", [])
    )


def _only_public_api(source: str) -> list[str]:
    """Imports of private names (``mobility._x`` or ``from mobility.x import _y``)."""
    bad = []
    for line in source.splitlines():
        words = line.replace(",", " ").split()
        if words[:1] in (["import"], ["from"]) and any(w.startswith("mobility") for w in words[1:2]):
            if any(part.startswith("_") for w in words[1:] for part in w.split(".") if w not in ("import", "as")):
                bad.append(line.strip())
    return bad


def test_notebooks_exist():
    assert len(NOTEBOOKS) >= 1


def test_every_notebook_runs_and_shows_pictures():
    async def run_all():
        return await asyncio.gather(*(_run(p) for p in NOTEBOOKS))

    results = asyncio.run(run_all())
    problems = []
    for path, nb, exc in results:
        if exc is not None:
            problems.append(f"{path.name}: {type(exc).__name__}: {str(exc).strip().splitlines()[-1] if str(exc).strip() else ''}")
            continue
        if _images(nb) == 0:
            problems.append(f"{path.name}: no picture among the outputs")
        for cell in nb.cells:
            if cell.cell_type == "code":
                private = _only_public_api(cell.source)
                if private:
                    problems.append(f"{path.name}: private import {private}")
    assert not problems, "\n".join(problems)


def test_private_import_detector():
    assert _only_public_api("from mobility.report.plotting import _scene") == ["from mobility.report.plotting import _scene"]
    assert _only_public_api("import mobility._x as y") == ["import mobility._x as y"]
    assert _only_public_api("from mobility.report.plotting import plot_mechanism, save_figure") == []
