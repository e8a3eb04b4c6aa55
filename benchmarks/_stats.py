"""What every benchmark shares: CPU time per call over runs, and the spread it reports (the median with the interquartile range)."""

from __future__ import annotations

import statistics
import time
from typing import Callable


def quartiles(values: list[float]) -> tuple[float, float, float]:
    """First quartile, median and third quartile of ``values`` (inclusive method: defined for two values or more)."""
    q = statistics.quantiles(values, n=4, method="inclusive")
    return q[0], statistics.median(values), q[2]


def run_times(fn: Callable[[], object], number: int, repeat: int) -> list[float]:
    """The mean CPU time (``time.process_time``) of ``number`` calls of ``fn``, in seconds, for each of ``repeat`` runs."""
    runs = []
    for _ in range(repeat):
        start = time.process_time()
        for _ in range(number):
            fn()
        runs.append((time.process_time() - start) / number)
    return runs


def median_time(fn: Callable[[], object], number: int, repeat: int) -> float:
    """Median over ``repeat`` runs of the mean CPU time of ``number`` calls, in seconds."""
    return statistics.median(run_times(fn, number, repeat))
