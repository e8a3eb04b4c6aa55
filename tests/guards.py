"""What the tests of hostile and extreme input assert: an answer within a time bound, and only finite numbers in it."""

from __future__ import annotations

import contextlib
import math
import signal
import time
from typing import Any, Iterator


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
