"""A long 1-D sweep: the two-level continuation against the one-level walk, measured in the same run.

Run:  python benchmarks/bench_sweep_line.py [--points 50000] [--repeat 3] [--markdown]

A 1-D sweep is one line, so the one-level continuation solves its points one
after the other: a Newton solve per point, each a few small batched numpy
calls.  The two-level walk (:func:`mobility.sweeps.continuation._leg`) solves
every ``k``-th point first, then the pieces between them all together.  Both
runs are :func:`mobility.sweep` of the planar four-bar's crank
(``mechanisms/four_bar.yaml``, ``A=0:10:POINTS``, every pose assembled), the
one-level one with ``TWO_LEVEL_LINES`` set beyond reach; their answers are
checked equal.  Times are medians of ``--repeat`` runs (wall clock); the
ratio is one-level over two-level, in the same run.
"""

from __future__ import annotations

import argparse
import os
import statistics
import time
from pathlib import Path

import numpy as np

import mobility
from mobility.sweeps import continuation, sweep

ROOT = Path(__file__).resolve().parent.parent


def timed(fn, repeat: int) -> tuple[float, list[float], object]:
    """Median wall time over ``repeat`` runs, every run's time, and the last result."""
    times, result = [], None
    for _ in range(repeat):
        start = time.perf_counter()
        result = fn()
        times.append(time.perf_counter() - start)
    return statistics.median(times), times, result


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--points", type=int, default=50_000)
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--markdown", action="store_true", help="print only the Markdown table")
    args = parser.parse_args()

    m = mobility.load(ROOT / "mechanisms" / "four_bar.yaml")
    vary = [f"A=0:10:{args.points}"]
    sweep(m, ["A=0:10:3"])  # build the model once
    two, two_runs, a = timed(lambda: sweep(m, vary), args.repeat)
    saved = continuation.TWO_LEVEL_LINES
    continuation.TWO_LEVEL_LINES = 10**18
    try:
        one, one_runs, b = timed(lambda: sweep(m, vary), args.repeat)
    finally:
        continuation.TWO_LEVEL_LINES = saved
    assert a.assembled.all() and b.assembled.all() and np.array_equal(a.pattern, b.pattern) and np.allclose(a.q, b.q, atol=1e-9), "the same answers"
    if not args.markdown:
        print(f"four-bar crank, {args.points:,} points, {args.repeat} runs")
    print(f"| four-bar crank, 1-D sweep of {args.points:,} points | two-level (wall) | one-level (baseline) | ratio |")
    print("|---|---:|---:|---:|")
    runs = lambda ts: ", ".join(f"{t:.2f}" for t in ts)  # noqa: E731
    print(f"| whole sweep | {two:.2f} s (runs: {runs(two_runs)}) | {one:.1f} s (runs: {runs(one_runs)}) | {one / two:.0f}x |")
    print(f"\nload average while it ran (1, 5, 15 min): {', '.join(f'{x:.1f}' for x in os.getloadavg())} on {os.cpu_count()} CPUs")


if __name__ == "__main__":
    main()
