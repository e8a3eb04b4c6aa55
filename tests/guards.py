"""What the tests of bad and extreme input assert, in one place: one line and exit 2, or an answer with finite numbers.

One helper per kind of assertion; the test files of bad input (``test_bad_*.py``) and of extreme input
(``test_extreme_*.py``, ``test_fuzz_files.py``) use these and no copy of their own:

* :func:`raises_one_line` -- a call of the Python API raises one of the project's errors, of one line;
* :func:`refused` -- a command ended in exit status 2 and one line ``mobility: ...`` on stderr, nothing on stdout,
  no traceback (in-process by :func:`run_cli`, or in a child process by :func:`run_child`);
* :func:`finite_numbers` -- an answer holds only finite numbers;
* :func:`time_bound` -- the block ends within a time bound (a hang fails the test, it does not stop the suite);
* :func:`run_all` and :func:`verdict` -- every command on one mechanism ends in exit 0 or 1 (an answer) whose
  printed and written numbers are all finite, with nothing on stderr but notes; or in exit 2 and one line.
"""

from __future__ import annotations

import contextlib
import io
import json
import math
import os
import re
import signal
import subprocess
import sys
import time
import warnings
from pathlib import Path
from typing import Any, Callable, Iterator

import pytest

import mobility
from mobility.core.model import Mechanism
from mobility.errors import MobilityError

PACKAGE_ROOT = str(Path(mobility.__file__).resolve().parent.parent)
"""The folder holding the package under test: a child process imports it from there."""


class TookTooLong(BaseException):
    """Raised by :func:`time_bound` when the guarded block runs past its bound.

    A ``BaseException``, like ``KeyboardInterrupt``: the command line's last-resort ``except Exception``
    must not turn it into an "internal error" of the code under test.
    """


@contextlib.contextmanager
def time_bound(seconds: float) -> Iterator[None]:
    """Interrupt the block after ``seconds`` (SIGALRM), keeping any timer already set (pytest-timeout's)."""

    def on_alarm(signum: int, frame: Any) -> None:
        raise TookTooLong(f"no answer within {seconds} s")

    old_handler = signal.signal(signal.SIGALRM, on_alarm)
    old_delay, old_interval = signal.setitimer(signal.ITIMER_REAL, seconds)
    start = time.monotonic()
    try:
        yield
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0)
        signal.signal(signal.SIGALRM, old_handler)
        if old_delay:
            signal.setitimer(signal.ITIMER_REAL, max(old_delay - (time.monotonic() - start), 0.001), old_interval)


def finite_numbers(value: Any) -> bool:
    """True when every number inside ``value`` (dicts, lists, tuples, arrays) is finite."""
    stack = [value]
    while stack:
        item = stack.pop()
        if isinstance(item, dict):
            stack.extend(item.values())
        elif isinstance(item, (list, tuple)):
            stack.extend(item)
        elif hasattr(item, "tolist"):
            stack.append(item.tolist())
        elif isinstance(item, float) and not math.isfinite(item):
            return False
    return True


def raises_one_line(call: Callable[[], Any], cls: type[BaseException] = MobilityError, match: str | None = None, *,
                    naming: tuple[str, ...] = (), shorter_than: int | None = None) -> Any:
    """Run ``call``: it must raise a ``cls`` (one of the project's errors) whose message is one line; return the error.

    ``match`` is searched in the message (``pytest.raises``); each word of ``naming`` (the function, the
    argument) must be in it, and with ``shorter_than`` it must be shorter than that many characters.
    """
    with pytest.raises(cls, match=match) as info:
        call()
    message = str(info.value)
    assert isinstance(info.value, MobilityError) and "\n" not in message, repr(info.value)
    assert shorter_than is None or len(message) < shorter_than, message
    assert all(word in message for word in naming), (naming, message)
    return info.value


def run_cli(*args: Any, seconds: float | None = None, warnings_as_errors: type[Warning] | None = None) -> subprocess.CompletedProcess[str]:
    """``mobility ARGS`` in-process (:func:`mobility.cli.main`), its stdout and stderr captured.

    An argparse refusal (``SystemExit``) is its exit status.  With ``seconds``, a run past the bound ends
    with status -1 and the reason as its stderr; with ``warnings_as_errors``, such a warning raises (it
    would otherwise reach stderr).
    """
    from mobility.cli import main

    argv = [str(a) for a in args]
    out, err = io.StringIO(), io.StringIO()
    with contextlib.ExitStack() as stack:
        if seconds is not None:
            stack.enter_context(time_bound(seconds))
        stack.enter_context(contextlib.redirect_stdout(out))
        stack.enter_context(contextlib.redirect_stderr(err))
        stack.enter_context(warnings.catch_warnings())
        if warnings_as_errors is not None:
            warnings.simplefilter("error", warnings_as_errors)
        try:
            status = main(argv)
        except SystemExit as stop:  # argparse's own refusal
            status = stop.code
        except TookTooLong as exc:
            if seconds is None:
                raise
            return subprocess.CompletedProcess(argv, -1, out.getvalue(), str(exc))
    return subprocess.CompletedProcess(argv, status, out.getvalue(), err.getvalue())


def run_child(*args: Any, env: dict[str, str] | None = None, cwd: Path | str | None = None, timeout: float = 60,
              memory_cap: int | None = None, unset: tuple[str, ...] = ()) -> subprocess.CompletedProcess[str]:
    """``mobility ARGS`` in a child process with the package under test, ended after ``timeout`` s (a hang fails, not waits).

    ``memory_cap`` caps the child's address space (bytes, ``RLIMIT_AS``): a blow-up ends there in a
    ``MemoryError`` instead of in the machine's swap.  ``unset`` names variables of this environment the
    child does not get.
    """
    environ = {k: v for k, v in os.environ.items() if k not in unset}
    environ.update(PYTHONPATH=PACKAGE_ROOT, **(env or {}))

    def cap() -> None:
        import resource

        resource.setrlimit(resource.RLIMIT_AS, (memory_cap, memory_cap))

    return subprocess.run([sys.executable, "-m", "mobility", *map(str, args)], capture_output=True, text=True, timeout=timeout,
                          env=environ, cwd=cwd, stdin=subprocess.DEVNULL, preexec_fn=cap if memory_cap else None)


def refused(done: subprocess.CompletedProcess[str], *, usage_error: bool = False) -> str:
    """Assert a run of the command line refused its input: exit 2, nothing on stdout, one line ``mobility: ...`` on stderr.

    With ``usage_error``, the line is argparse's own refusal of an option, ``mobility COMMAND: error: ...``.
    Return that line (without its line break) for the test to check its words.
    """
    assert (done.returncode, done.stdout) == (2, ""), (done.returncode, done.stdout[-300:], done.stderr[-2000:])
    assert done.stderr.count("\n") == 1 and done.stderr.endswith("\n") and "Traceback" not in done.stderr, done.stderr[-2000:]
    prefix = r"mobility [a-z]+: error: " if usage_error else "mobility: "
    assert re.match(prefix, done.stderr), done.stderr
    return done.stderr[:-1]


# -- every command on one mechanism: an answer with finite numbers, or one line and exit 2 ---------------------------


RUN_BOUND = 60.0
"""Seconds one command may take before the guard stops it (a hang, not a slow run: every run here
takes a few seconds at most)."""


def sweep_range(m: Mechanism) -> str:
    """A small sweep of the first drivable joint: 5 degrees, or 1 % of the mechanism's size for a slider."""
    joint = next(j for j in m.joints if j.type in "RPHC")
    if joint.type != "P":
        return f"{joint.name}=0:5:3"
    from mobility.core.joint_screws import joint_screws

    return f"{joint.name}=0:{0.01 * joint_screws(m).normalisation.length!r}:3"


def commands(m: Mechanism, path: Path, out: Path) -> dict[str, list[str]]:
    """Every command and option under test, on the file ``path``, writing into the folder ``out``."""
    f = str(path)
    return {
        "analyze": ["analyze", "--json", f],
        "analyze --finite": ["analyze", "--finite", f],
        "check": ["check", "--json", f],
        "actuation": ["actuation", "--json", f],
        "actuation --enumerate": ["actuation", "--enumerate", "--json", f],
        "actuation --samples": ["actuation", "--samples", "2", "--json", f],
        "plot": ["plot", "--constraints", f, "-o", str(out / "picture.png"), "--dpi", "30"],
        "plot --graph": ["plot", "--graph", f, "-o", str(out / "graph.png"), "--dpi", "30"],
        "jacobian": ["jacobian", "--json", f],
        "sweep": ["sweep", f, "--vary", sweep_range(m), "--json", "--no-progress"],
        "view": ["view", f, "-o", str(out / "view.html")],
        "view --samples": ["view", "--samples", "2", f, "-o", str(out / "samples.html")],
        "convert": ["convert", f, "-o", str(out / "converted.yaml")],
    }


NON_FINITE = re.compile(r"(?<![\w.])(nan|-?inf|NaN|-?Infinity)(?![\w.])")


def page_figure(html: str) -> Any:
    """The figure (data and layout) that a page of ``mobility view`` hands to plotly."""
    call = html.rindex("Plotly.newPlot(")
    text = html[html.index("[", call):]
    decoder = json.JSONDecoder()
    data, end = decoder.raw_decode(text)
    layout, _ = decoder.raw_decode(text[end:].lstrip(" ,\n"))
    return {"data": data, "layout": layout}


def written_numbers_are_finite(args: list[str]) -> str:
    """'' when the file a run wrote (picture, page, converted file) is there and its numbers are finite, else why not."""
    if "-o" not in args:
        return ""
    path = Path(args[args.index("-o") + 1])
    if not path.exists() or path.stat().st_size == 0:
        return f"{path.name} was not written"
    if path.suffix == ".html":
        figure = page_figure(path.read_text(encoding="utf-8"))
        return "" if finite_numbers(figure) and "NaN" not in json.dumps(figure) else f"{path.name}: a number of the figure is not finite"
    if path.suffix == ".yaml":
        back = mobility.load(path)  # what was written reads back
        numbers = [x for j in back.world_joints for v in (j.point, j.axis, j.normal) if v is not None for x in v]
        return "" if all(math.isfinite(x) for x in numbers) else f"{path.name}: a number is not finite"
    return ""


def verdict(args: list[str], status: int, out: str, err: str) -> str:
    """'' when the run ended as the contract says, else what went wrong (for the failure message)."""
    if status == 2 and args[0] == "check" and not err:  # check reports a bad file in its table, one line each
        rows = json.loads(out)["results"]
        return "" if all(r["status"] != "error" or "\n" not in r["message"] for r in rows) else "check: an error of several lines"
    if status == 2:
        return "" if err.count("\n") == 1 and err.startswith("mobility: ") else f"exit 2 but stderr is not one line: {err[:300]!r}"
    if status not in (0, 1):
        return f"exit {status}: {err.strip()[:300]}"
    noise = [line for line in err.splitlines() if not line.startswith(("mobility: note: ", "mobility: wrote "))]
    if noise:
        return f"exit {status} with stderr: {noise[0][:300]}"
    try:
        printed = json.loads(out)
    except ValueError:
        if NON_FINITE.search(out):
            return f"a non-finite number printed: {NON_FINITE.search(out).group(0)!r}"
    else:
        if not finite_numbers(printed):
            return "a non-finite number in the JSON printed"
    return written_numbers_are_finite(args)


def run_all(m: Mechanism, folder: Path) -> dict[str, tuple[int, str]]:
    """Write ``m`` to ``folder`` and run every command on it: ``{command: (exit status, what went wrong or '')}``."""
    path = folder / "mechanism.yaml"
    from builders import yaml_text

    path.write_text(yaml_text(m), encoding="utf-8")
    outcome = {}
    for name, args in commands(m, path, folder).items():
        done = run_cli(*args, seconds=RUN_BOUND, warnings_as_errors=RuntimeWarning)  # a numpy warning would reach stderr
        outcome[name] = (done.returncode, verdict(args, done.returncode, done.stdout, done.stderr))
    return outcome
