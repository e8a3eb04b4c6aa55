"""Analyses per second for every bundled mechanism, the two routes side by side.

Run:  python benchmarks/bench_analyze.py [--number N] [--repeat R] [--markdown]

For each mechanism (loaded once) it times

* ``analyze``: :func:`mobility.analyze` on the loaded model.  What a
  mechanism object keeps between calls is only what describes the model: its
  frames resolved, its joints' elementary freedoms tabulated as unit twists,
  and its series/parallel decomposition (which depends on the joint graph
  only); every screw system, rank decision and count is computed anew;
* ``rebuilt``: the same with the joint-twist table dropped before each call
  (what a new pose of a sweep pays on top);
* ``+ directions``: ``rebuilt`` plus the canonical directions (translations,
  rotations, constraint wrenches), which :class:`mobility.Result` computes on
  first access;
* ``loop closure``: the independent route of :mod:`mobility.core.loop_closure`
  (one constraint Jacobian of the whole graph, its twist table rebuilt too),
  the baseline of the ratio.

Times are CPU time of this process (``time.process_time``, so other busy
processes on a shared machine count less than in wall time): for each of
``repeat`` runs the mean of ``number`` calls, then the median over the runs;
the spread of ``analyze`` is given as the interquartile range over the runs.
Ratios are against the loop-closure route measured in the same run, so they
hold across machines better than the times.  Target: ``analyze`` of the
loaded 3-PRS at most 100 µs.
"""

from __future__ import annotations

import argparse
import os
import sys
import time
from pathlib import Path

import mobility
from mobility.core import joint_screws as js_module
from mobility.core.loop_closure import loop_closure
from _stats import median_time, quartiles, run_times

ROOT = Path(__file__).resolve().parent.parent


def rebuilt(m: mobility.Mechanism):
    """A call that analyses ``m`` with its joint-twist table rebuilt."""

    def call():
        js_module.clear_cache(m)
        return mobility.analyze(m)

    return call


def with_directions(m: mobility.Mechanism):
    def call():
        js_module.clear_cache(m)
        r = mobility.analyze(m)
        return r.rotations, r.forces

    return call


def baseline(m: mobility.Mechanism):
    def call():
        js_module.clear_cache(m)
        return loop_closure(m)

    return call


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--number", type=int, default=200)
    parser.add_argument("--repeat", type=int, default=7)
    parser.add_argument("--markdown", action="store_true", help="print a Markdown table")
    parser.add_argument("files", nargs="*", help="mechanism files (default: mechanisms/*.yaml)")
    args = parser.parse_args()
    files = [Path(f) for f in args.files] or sorted((ROOT / "mechanisms").glob("*.yaml"))
    rows = []
    warm = mobility.load(files[0])
    start = time.process_time()
    while time.process_time() - start < 1.0:  # the first second runs slow (frequency scaling, caches): not measured
        mobility.analyze(warm)
    for path in files:
        m = mobility.load(path)
        r = mobility.analyze(m)
        runs = run_times(lambda: mobility.analyze(m), args.number, args.repeat)
        q1, t_an, q3 = quartiles(runs)
        t_re = median_time(rebuilt(m), args.number, args.repeat)
        t_dir = median_time(with_directions(m), max(1, args.number // 2), args.repeat)
        t_lc = median_time(baseline(m), max(1, args.number // 2), args.repeat)
        rows.append((path.stem, len(m.joints), r.pattern, t_an, (q1, q3), t_re, t_dir, t_lc))
    if args.markdown:
        print("| mechanism | joints | pattern | analyze (µs) [IQR] | analyses/s | rebuilt (µs) | + directions (µs) | loop closure (µs) | loop closure / rebuilt |")
        print("|---|---:|---|---:|---:|---:|---:|---:|---:|")
        for name, j, pat, a, (lo, hi), re_, d, lc in rows:
            print(f"| {name} | {j} | {pat} | {a * 1e6:.0f} [{lo * 1e6:.0f}–{hi * 1e6:.0f}] | {1 / a:,.0f} | {re_ * 1e6:.0f} | {d * 1e6:.0f} | {lc * 1e6:.0f} | {lc / re_:.1f}× |")
    else:
        print(f"{'mechanism':28s} {'joints':>6s} {'pattern':>8s} {'analyze µs':>11s} {'IQR':>11s} {'per s':>8s} {'rebuilt':>8s} {'+dirs µs':>9s} {'loop µs':>8s} {'ratio':>6s}")
        for name, j, pat, a, (lo, hi), re_, d, lc in rows:
            print(f"{name:28s} {j:6d} {pat:>8s} {a * 1e6:11.0f} {lo * 1e6:5.0f}-{hi * 1e6:<5.0f} {1 / a:8,.0f} {re_ * 1e6:8.0f} {d * 1e6:9.0f} {lc * 1e6:8.0f} {lc / re_:5.1f}x")
    print(f"\n{args.repeat} runs of {args.number} calls; Python {sys.version.split()[0]}; {os.cpu_count()} CPUs; load average {os.getloadavg()[0]:.1f}")


if __name__ == "__main__":
    main()
