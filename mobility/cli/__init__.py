"""The ``mobility`` command line.

Each subcommand is a module of this package named after it, with ``register(subparsers)`` (adding its
parser and setting ``run(args) -> int``), an ``ORDER`` in ``mobility --help`` and, for a command with a
verdict, ``EXIT_STATUS``.  :func:`main` imports only the module of the command asked for.  The exit
statuses, outputs and the escaping of what the terminal cannot show are described in the README.
"""

from __future__ import annotations

import argparse
import codecs
import contextlib
import importlib
import logging
import os
import pkgutil
import signal
import sys
import traceback
import warnings
from typing import Any, NoReturn, Sequence

from ..errors import MobilityError, RequestError, one_line
from ..io.files import os_reason
from ..outputs import interrupting_signal, interrupts_end_at_commit, terminate_as_interrupt

__all__ = ["main", "build_parser", "command_modules", "command_names", "options_given", "SUCCESS_OR_BAD_INPUT"]

SUCCESS_OR_BAD_INPUT = "0 success, 2 bad input (one line on standard error)"
"""The exit statuses of a command without a verdict; a module with one says its own in ``EXIT_STATUS`` (shown by its ``--help``)."""


def command_names() -> list[str]:
    """The names of the subcommand modules of this package (found without importing them)."""
    return sorted(info.name for info in pkgutil.iter_modules(__path__) if not info.name.startswith("_"))


def command_modules(names: Sequence[str] | None = None) -> list:
    """The subcommand modules of this package (those of ``names`` only, if given), in ``ORDER``."""
    mods = [importlib.import_module(f"{__name__}.{name}") for name in (command_names() if names is None else names)]
    return sorted((m for m in mods if hasattr(m, "register")), key=lambda m: (getattr(m, "ORDER", 100), m.__name__))


class _Parser(argparse.ArgumentParser):
    def error(self, message: str) -> NoReturn:  # one line, exit 2 (the usage is one --help away)
        self.exit(2, f"{self.prog}: error: {message} (see {self.prog} --help)\n")


def build_parser(commands: Sequence[str] | None = None) -> argparse.ArgumentParser:
    """The argument parser with every registered subcommand (those of ``commands`` only, if given)."""
    from .. import __version__

    parser = _Parser(prog="mobility", description="Mobility analysis of mechanisms by screw theory.")
    parser.add_argument("--version", action="version", version=f"mobility {__version__}")
    parser.add_argument("--debug", action="store_true", help="show a traceback on internal errors")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND", parser_class=_Parser)
    sub.required = True
    for module in command_modules(commands):
        module.register(sub)
        command = sub.choices[module.__name__.rpartition(".")[2]]
        command.epilog = f"Exit status: {getattr(module, 'EXIT_STATUS', SUCCESS_OR_BAD_INPUT)}; 3 an internal error; 130 interrupted; 143 terminated."
        # after the command too (`mobility analyze f --debug`), as the internal-error message suggests; unset unless given
        command.add_argument("--debug", action="store_true", default=argparse.SUPPRESS, help="show a traceback on internal errors")
    return parser


def _command_asked(argv: Sequence[str]) -> list[str] | None:
    """``[name]`` when the first word of ``argv`` that is not an option names a subcommand module, else None (every module)."""
    for word in argv:
        if not word.startswith("-"):
            return [word] if word in command_names() else None
        if word in ("-h", "--help"):
            return None
    return None


def options_given(argv: Sequence[str]) -> frozenset[str]:
    """The destinations (``max_poses``, ``step``...) of the options typed in ``argv``, not left at their defaults.

    ``argv`` is parsed again with every default suppressed, so that ``--step 0.1``
    counts as given even at its default (for :func:`mobility.cli._options.require_option_for`).

    Examples
    --------
    >>> sorted(options_given(["view", "f.yaml", "-o", "v.html", "--step", "0.1"]))
    ['command', 'file', 'output', 'run', 'step']
    """
    parser = build_parser(_command_asked(argv))
    seen: set[int] = set()

    def suppress(p: argparse.ArgumentParser) -> None:
        if id(p) in seen:
            return
        seen.add(id(p))
        for action in p._actions:
            if isinstance(action, argparse._SubParsersAction):
                for child in action.choices.values():
                    suppress(child)
            action.default = argparse.SUPPRESS

    suppress(parser)
    try:
        return frozenset(vars(parser.parse_args(argv)))
    except SystemExit:  # pragma: no cover - argv was parsed once already
        return frozenset()


class _GuardedOutput:
    """Standard output for the length of a command: a failed write (``ENOSPC``) is a :class:`RequestError`, not an internal error.

    After a ``BrokenPipeError`` later writes are dropped (the command ends with its own status); ``stream`` is None when stdout was closed.
    """

    def __init__(self, stream: Any) -> None:
        self.stream, self.failed, self.reader_gone = stream, False, False

    def _guarded(self, action: Any, *args: Any) -> Any:
        if self.reader_gone:
            return None
        try:
            return action(*args)
        except OSError as exc:
            self.failed = True
            if isinstance(exc, BrokenPipeError):
                self.reader_gone = True  # drop the rest: the command still runs to its own exit status
                return None
            raise RequestError(f"cannot write it ({os_reason(exc)})", argument="standard output") from None

    def write(self, text: str) -> int:
        if self.stream is None:  # started with standard output closed (`>&-`): Python has none
            self.failed = True
            raise RequestError("cannot write it (it is closed)", argument="standard output")
        self._guarded(self.stream.write, text)
        return len(text)

    def flush(self) -> None:
        if self.stream is not None:
            self._guarded(self.stream.flush)

    def __getattr__(self, name: str) -> Any:
        return getattr(self.stream, name)


def _discard_stdout() -> None:
    """Point the process's standard output at ``os.devnull`` after a write to it failed; a test's capture is left alone.

    Its buffer would otherwise fail again at exit (exit status 120), as the :mod:`signal` documentation warns for ``SIGPIPE``.
    """
    if sys.stdout is not sys.__stdout__ or sys.stdout is None:
        return
    try:
        fd = sys.stdout.fileno()
    except (OSError, ValueError):  # no descriptor (io.UnsupportedOperation is both)
        return
    with open(os.devnull, "wb") as devnull:
        os.dup2(devnull.fileno(), fd)


ESCAPE_ERRORS = "mobility.escape"
"""The codec error handler of the standard streams: a character their encoding lacks is written ``\\uXXXX``."""


def _unicode_escapes(exc: UnicodeError) -> tuple[str, int]:
    r"""``\uXXXX`` for each character that cannot be encoded (a surrogate pair beyond the BMP): a JSON escape, so JSON stays JSON.

    Examples
    --------
    >>> "Gr\u00fcbler \U0001F600".encode("ascii", errors=ESCAPE_ERRORS)
    b'Gr\\u00fcbler \\ud83d\\ude00'
    """
    if not isinstance(exc, UnicodeEncodeError):
        raise exc
    units = exc.object[exc.start : exc.end].encode("utf-16-be", "surrogatepass")  # a pair beyond the BMP, as JSON writes it
    return "".join(f"\\u{units[i]:02x}{units[i + 1]:02x}" for i in range(0, len(units), 2)), exc.end


codecs.register_error(ESCAPE_ERRORS, _unicode_escapes)


def _escape_what_cannot_be_encoded() -> None:
    """Write characters that the standard streams' encoding lacks (``ü`` on an ASCII terminal) as ``\\u00fc`` (JSON's escape), not an error."""
    for stream in (sys.stdout, sys.stderr):
        reconfigure = getattr(stream, "reconfigure", None)
        if reconfigure is not None:
            with contextlib.suppress(OSError, ValueError):
                reconfigure(errors=ESCAPE_ERRORS)


@contextlib.contextmanager
def _stderr_or_nothing() -> Any:
    """Standard error as it is, or a sink when the process was started without one (``2>&-``: ``print(file=None)`` writes to stdout)."""
    if sys.stderr is not None:
        yield
        return
    with open(os.devnull, "w", encoding="utf-8") as sink, contextlib.redirect_stderr(sink):
        yield


def main(argv: Sequence[str] | None = None) -> int:
    """Run the command line; returns the exit status (standard output flushed first, so that a failure to write it is reported)."""
    whole_process = argv is None  # the command is the program: once its output is in place, it ends as it succeeded
    argv = list(sys.argv[1:] if argv is None else argv)
    _escape_what_cannot_be_encoded()
    with _stderr_or_nothing(), warnings.catch_warnings(), _log_lines_as_notes(), terminate_as_interrupt(), interrupts_end_at_commit(to_the_end=whole_process):
        warnings.showwarning = _warning_as_a_note
        return _run(argv)


class _NoteHandler(logging.Handler):
    """A library's log record of warning level or above (matplotlib's about its cache folder...) written as one ``mobility: note:`` line."""

    def emit(self, record: logging.LogRecord) -> None:
        try:
            print(f"mobility: note: {one_line(record.getMessage())}", file=sys.stderr)
        except Exception:  # a message that cannot be formatted or written: dropped, never a traceback
            pass


@contextlib.contextmanager
def _log_lines_as_notes() -> Any:
    """For the length of a command, log records that would reach standard error (Python's last-resort handler) become note lines."""
    root = logging.getLogger()
    if root.handlers:  # the program that called main() chose where its logs go
        yield
        return
    handler = _NoteHandler(logging.WARNING)
    root.addHandler(handler)
    try:
        yield
    finally:
        root.removeHandler(handler)


def _warning_as_a_note(message: Any, category: type, filename: str, lineno: int, file: Any = None, line: str | None = None) -> None:
    """A Python warning (a library's: matplotlib, numpy...) shown as one line, ``mobility: note: ...``, not with its source line."""
    print(f"mobility: note: {one_line(str(message))}", file=sys.stderr)


def _run(argv: list[str]) -> int:
    """:func:`main` with its streams in place: the command, its errors turned into exit statuses."""
    out = _GuardedOutput(sys.stdout)
    args = None
    try:
        with contextlib.redirect_stdout(out):
            try:
                args = build_parser(_command_asked(argv)).parse_args(argv)
                args.given_options = options_given(argv)
                return int(args.run(args) or 0)
            finally:  # --help and --version too (their SystemExit passes through, unless the flush fails)
                out.flush()
    except MobilityError as exc:
        print(f"mobility: {one_line(str(exc))}", file=sys.stderr)
        return 2
    except KeyboardInterrupt:  # Ctrl-C (or SIGTERM): one line, the shell's status for the signal
        signum = interrupting_signal()
        print("mobility: interrupted" if signum == signal.SIGINT else "mobility: terminated", file=sys.stderr)
        return 128 + signum
    except MemoryError:  # a request too large for this machine: said in one line, like any request out of range
        print("mobility: out of memory: the request needs more memory than this machine has free; "
              "ask for less (a coarser grid or fewer poses: --max-poses; fewer samples)", file=sys.stderr)
        return 2
    except Exception as exc:  # an internal error: one line unless --debug
        if args is not None and args.debug:
            traceback.print_exc()
        else:
            print(f"mobility: internal error ({type(exc).__name__}: {one_line(str(exc))}); rerun with --debug and please report it", file=sys.stderr)
        return 3
    finally:
        if out.failed:
            _discard_stdout()
