"""Reading document files within the size limit, whatever they are (a FIFO, ``/dev/zero``, ``/dev/kmsg``, a huge file, a symbolic link loop).

Only a regular file is read (reading ``/dev/kmsg`` or a FIFO waits for ever);
:func:`os_reason` and :func:`printable_name` say a path's trouble and name in a message.

Examples
--------
>>> import tempfile, os
>>> with tempfile.NamedTemporaryFile("wb", delete=False) as f:
...     _ = f.write(b"name: m")
>>> read_capped(f.name)
b'name: m'
>>> read_capped("/dev/zero")
Traceback (most recent call last):
...
mobility.errors.MechanismFileError: /dev/zero: is a device (a terminal, /dev/zero...), not a regular file; expected a mechanism file
>>> os.unlink(f.name)
"""

from __future__ import annotations

import errno
import os
import stat
import sys
from pathlib import Path
from typing import BinaryIO

from ..errors import MechanismFileError, RequestError, clipped
from .limits import Limits, current_limits

__all__ = ["read_capped", "open_regular", "file_name", "require_not_pipe", "is_regular_file", "os_reason", "printable_name"]


def os_reason(exc: OSError) -> str:
    """What an ``OSError`` met on a path says, in words for a one-line message (a symbolic link loop named as such).

    Examples
    --------
    >>> import errno, os
    >>> os_reason(OSError(errno.ELOOP, os.strerror(errno.ELOOP)))
    'a symbolic link loop (too many levels of symbolic links)'
    >>> os_reason(OSError(errno.ENOSPC, "No space left on device"))
    'No space left on device'
    """
    if exc.errno == errno.ELOOP:
        return "a symbolic link loop (too many levels of symbolic links)"
    return exc.strerror or str(exc)


def printable_name(name: str | os.PathLike[str]) -> str:
    """``name`` as text that any output takes: the bytes of a file name that the file system's encoding cannot decode (lone
    surrogates in Python, invalid UTF-8 once written) shown as ``\\xNN``; every name a report prints goes through this.

    Examples
    --------
    >>> import os
    >>> printable_name(os.fsdecode(b"bad\\xff\\xfename.yaml"))
    'bad\\\\xff\\\\xfename.yaml'
    >>> printable_name("caf\u00e9.yaml")
    'café.yaml'
    """
    text = os.fspath(name)
    try:
        raw = os.fsencode(text)
    except UnicodeEncodeError:  # a surrogate that stands for no byte (not from a file name): escape it as a code point
        return text.encode("utf-8", "backslashreplace").decode("utf-8")
    return raw.decode(sys.getfilesystemencoding(), "backslashreplace")


def require_not_pipe(path: str | Path, expected: str = "a mechanism file") -> int:
    """The file type bits of ``path`` (0 if it cannot be stat-ed), a :class:`~mobility.errors.MechanismFileError` for a pipe or
    socket, without opening it (that waits for a writer)."""
    try:
        kind = os.stat(path).st_mode
    except (OSError, ValueError):
        return 0  # missing or unreadable: opening it says which
    if stat.S_ISFIFO(kind) or stat.S_ISSOCK(kind):
        raise MechanismFileError("", f"is a pipe or socket, expected {expected}", file=str(path))
    return kind


def is_regular_file(path: str | Path) -> bool:
    """Whether ``path`` is a regular file (a pipe or socket is refused, see :func:`require_not_pipe`); never opens it."""
    return stat.S_ISREG(require_not_pipe(path))


def file_name(value: object, what: str) -> str:
    """``value`` as the name of a file to read: a ``str`` or ``os.PathLike`` without a NUL (``open`` would take an ``int`` for a
    descriptor of the caller's, read it and close it), else a :class:`~mobility.errors.RequestError` naming ``what`` first.

    Examples
    --------
    >>> file_name(Path("arm.urdf"), "load")
    'arm.urdf'
    >>> file_name(1, "closures")
    Traceback (most recent call last):
    ...
    mobility.errors.RequestError: closures: expected a file name (str or Path), got int
    >>> file_name("a\\x00b.yaml", "load")
    Traceback (most recent call last):
    ...
    mobility.errors.RequestError: load: expected a file name without a NUL character, got 'a\\x00b.yaml'
    """
    name: object = None
    if isinstance(value, (str, os.PathLike)):
        try:
            name = os.fspath(value)
        except TypeError:  # an __fspath__ that returns neither str nor bytes
            name = None
    if not isinstance(name, str):
        raise RequestError(caller=what, expected="a file name (str or Path)", got=type(value).__name__)
    if "\x00" in name:
        raise RequestError(caller=what, expected="a file name without a NUL character", got=repr(clipped(name, 80)))  # repr: one line
    return name


def _not_regular(mode: int) -> str | None:
    """What a file of type bits ``mode`` is, when it is not a regular file (``None`` for a regular one)."""
    if stat.S_ISREG(mode):
        return None
    if stat.S_ISDIR(mode):
        return "is a directory"
    if stat.S_ISFIFO(mode) or stat.S_ISSOCK(mode):
        return "is a pipe or socket"
    return "is a device (a terminal, /dev/zero...), not a regular file"


def open_regular(path: str | Path, expected: str = "a mechanism file") -> BinaryIO:
    """``path`` opened for reading in binary, when it is a regular file; anything else refused in one line before it is opened.

    Its type is checked from its ``stat``, then again on the descriptor opened
    with ``O_NONBLOCK`` (a pipe swapped in between); ``expected``: what the file should be.

    Raises
    ------
    MechanismFileError
        One line naming the file: missing, a directory, a pipe, a device, a
        symbolic link loop or unreadable.
    """
    name = file_name(path, "read")  # never a descriptor of the caller's (an int), nor a NUL in a name; a message escapes what is not text
    try:
        what = _not_regular(os.stat(name).st_mode)
        if what is None:
            flags = os.O_RDONLY | getattr(os, "O_NONBLOCK", 0) | getattr(os, "O_NOCTTY", 0) | getattr(os, "O_CLOEXEC", 0) | getattr(os, "O_BINARY", 0)
            fd = os.open(name, flags)
            try:
                what = _not_regular(os.fstat(fd).st_mode)
            except OSError:
                os.close(fd)
                raise
            if what is None:
                return os.fdopen(fd, "rb")
            os.close(fd)
    except FileNotFoundError:
        raise MechanismFileError("", "no such file", file=name) from None
    except OSError as exc:
        if exc.errno == errno.ELOOP:
            raise MechanismFileError("", f"is {os_reason(exc)}, expected {expected}", file=name) from None
        raise MechanismFileError("", f"cannot read: {os_reason(exc)}", file=name) from None
    joined = "; " if what.endswith("not a regular file") else ", "
    raise MechanismFileError("", f"{what}{joined}expected {expected}", file=name)


def read_capped(path: str | Path, limits: Limits | None = None) -> bytes:
    """The bytes of a regular file, read with the size cap of ``limits`` (never more than the cap plus one chunk).

    Raises
    ------
    MechanismFileError
        As :func:`open_regular`, or when unreadable or larger than the limit.
    """
    cap = current_limits(limits).max_file_bytes
    with open_regular(path) as stream:
        name = os.fspath(path)
        try:
            chunks, size = [], 0
            while size <= cap:  # in chunks: read(cap + 1) would allocate the whole cap for every file
                chunk = stream.read(min(1 << 16, cap + 1 - size))
                if chunk is None:  # nothing to read yet (/proc/kmsg): reading it would wait
                    raise MechanismFileError("", "cannot read without waiting (a file of the kernel that is read as it is written); expected a mechanism file", file=name)
                if not chunk:
                    break
                chunks.append(chunk)
                size += len(chunk)
            raw = b"".join(chunks)
        except OSError as exc:
            raise MechanismFileError("", f"cannot read: {os_reason(exc)}", file=name) from None
    if len(raw) > cap:
        raise MechanismFileError("", f"larger than the limit of {cap} bytes for a document (set MOBILITY_MAX_FILE_BYTES to raise it)", file=name)
    return raw
