"""Output files written whole or not at all: the one way the package writes a user's file.

:func:`atomic_output` writes ``.NAME.XXXXXXXX.tmp`` beside the target, flushes
it (``fsync``) and puts it in place with :func:`os.replace` (atomic on one file
system).  On any failure or interrupt (``SIGINT``; ``SIGTERM`` under
:func:`terminate_as_interrupt`) the temporary file is removed and the previous
target left byte for byte; creating, renaming and removing it run with both
signals held back, so no interrupt can leave it behind.  A target that is not
a regular file (``/dev/null``, a pipe) is written in place; a symbolic link is
followed.

Examples
--------
>>> import os, tempfile
>>> folder = tempfile.mkdtemp()
>>> target = os.path.join(folder, "table.csv")
>>> with atomic_output(target) as handle:
...     _ = handle.write("a,b\\n")
>>> open(target).read(), os.listdir(folder)
('a,b\\n', ['table.csv'])
>>> try:
...     with atomic_output(target) as handle:
...         _ = handle.write("half a ta")
...         raise KeyboardInterrupt
... except KeyboardInterrupt:
...     pass
>>> open(target).read(), os.listdir(folder)
('a,b\\n', ['table.csv'])
"""

from __future__ import annotations

import contextlib
import os
import signal
import stat
import threading
from typing import IO, Any, Iterator

__all__ = ["atomic_output", "held_signals", "interrupts_end_at_commit", "terminate_as_interrupt", "interrupting_signal", "HELD"]

HELD = (signal.SIGINT, signal.SIGTERM)
"""The signals held back while a temporary file is created, renamed or removed."""

_received: list[int] = []


@contextlib.contextmanager
def held_signals() -> Iterator[None]:
    """:data:`HELD` held back for the duration, then delivered (in the main thread; elsewhere nothing to do: Python runs handlers there only).

    The handlers are swapped for a recording one rather than the signals
    blocked: any thread may take a signal, and Python runs the handler in the
    main thread whatever its mask.
    """
    previous = _defer()
    try:
        yield
    finally:
        _deliver(previous)


def _defer() -> dict[int, Any] | None:
    """Put the recording handler in place of :data:`HELD`'s; the previous handlers (``None`` outside the main thread, or when already deferred)."""
    if threading.current_thread() is not threading.main_thread() or _hold["handlers"] is not None:
        return None
    return {s: signal.signal(s, _record) for s in HELD}


def _deliver(previous: dict[int, Any] | None) -> None:
    """Restore the handlers of :func:`_defer`, then deliver what arrived meanwhile (unless :func:`interrupts_end_at_commit` holds them)."""
    if previous is None:
        return
    for s, handler in previous.items():
        signal.signal(s, handler)
    arrived, _pending[:] = list(_pending), []
    for s in dict.fromkeys(arrived):
        handler = previous[s]
        if callable(handler):
            handler(s, None)
        elif handler == signal.SIG_DFL:
            signal.raise_signal(s)


_pending: list[int] = []


def _record(signum: int, frame: Any) -> None:
    _pending.append(signum)


def _temporary(target: str, binary: bool, encoding: str | None) -> tuple[str, IO[Any]]:
    """A new file beside ``target``, created with the permissions of a new file (``0o666`` less the umask), open for writing."""
    folder, name = os.path.split(target)
    while True:
        temp = os.path.join(folder, f".{name}.{os.urandom(4).hex()}.tmp")
        try:
            fd = os.open(temp, os.O_WRONLY | os.O_CREAT | os.O_EXCL | getattr(os, "O_CLOEXEC", 0), 0o666)
            break
        except FileExistsError:
            continue
    try:
        handle = os.fdopen(fd, "wb" if binary else "w", encoding=None if binary else encoding)
    except BaseException:
        os.close(fd)
        os.unlink(temp)
        raise
    return temp, handle


@contextlib.contextmanager
def atomic_output(path: str | os.PathLike[str], *, binary: bool = False, encoding: str = "utf-8") -> Iterator[IO[Any]]:
    """A file handle whose content replaces ``path`` only when the block ends without an exception (see the module docstring).

    ``binary`` gives a ``bytes`` handle.  An :class:`OSError` of the file
    system leaves the previous file intact and no temporary file.
    """
    target = os.fspath(path)
    if os.path.islink(target):
        target = os.path.realpath(target)
    try:
        mode = os.stat(target).st_mode
    except OSError:
        mode = None
    if mode is not None and not stat.S_ISREG(mode):  # a device or a pipe: written in place, nothing to replace
        with open(target, "wb" if binary else "w", encoding=None if binary else encoding) as direct:
            yield direct
        return
    temp, handle = "", None
    try:
        with held_signals():
            temp, handle = _temporary(target, binary, encoding)
        with handle:
            yield handle
            handle.flush()
            os.fsync(handle.fileno())
        if mode is not None:  # the previous file's permissions kept
            os.chmod(temp, stat.S_IMODE(mode))
        previous = _defer()
        try:
            os.replace(temp, target)
            temp = ""
        finally:
            if _hold["active"] and previous is not None:  # held from now on, until the command ends
                _hold["handlers"] = previous
                _pending.clear()
            else:
                _deliver(previous)
    finally:
        if handle is not None and not handle.closed:
            with held_signals(), contextlib.suppress(OSError):
                handle.close()
        if temp:
            with held_signals(), contextlib.suppress(OSError):
                os.unlink(temp)


_hold: dict[str, Any] = {"active": False, "handlers": None}


@contextlib.contextmanager
def interrupts_end_at_commit(*, to_the_end: bool = False) -> Iterator[None]:
    """For a command: once an output is in place, ``SIGINT`` and ``SIGTERM`` are held back until the end, then dropped.

    A complete output then ends as a success (status 0), never as an
    interrupt; one before the output is in place leaves the previous file and
    the interrupt's status.  With ``to_the_end`` (the command is the process)
    they stay ignored after the block instead of getting their handlers back.
    """
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    _hold.update(active=True, handlers=None)
    try:
        yield
    finally:
        handlers = _hold["handlers"]
        _hold.update(active=False, handlers=None)
        if handlers is not None:
            for s, handler in handlers.items():
                signal.signal(s, signal.SIG_IGN if to_the_end else handler)
            _pending.clear()


def _interrupt(signum: int, frame: Any) -> None:
    _received.append(signum)
    raise KeyboardInterrupt


@contextlib.contextmanager
def terminate_as_interrupt() -> Iterator[None]:
    """``SIGTERM`` raised as :class:`KeyboardInterrupt` for the duration, as ``SIGINT`` is, so that outputs are cleaned up (main thread only).

    :func:`interrupting_signal` then tells which signal it was.
    """
    _received.clear()
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    previous = signal.signal(signal.SIGTERM, _interrupt)
    try:
        yield
    finally:
        signal.signal(signal.SIGTERM, previous)


def interrupting_signal() -> int:
    """The signal of the last interrupt within :func:`terminate_as_interrupt`: ``SIGTERM``, else ``SIGINT``."""
    return _received[-1] if _received else int(signal.SIGINT)
