"""First analysis of large mechanisms, and how it grows with the number of joints.

Run:  python benchmarks/bench_large.py [--runs N] [--markdown]

Three families, each at 1/8, 1/4, 1/2 and 1 of its largest size:

* a serial **chain** of revolute joints in general position (up to 2,000
  joints: one series node of 2,000 children);
* a planar **ladder** of rigid triangles, ``A{i}: R [g, l{i}]`` and
  ``B{i}: R [l{i}, l{i+1}]`` (up to 500 loops, 1,001 joints: series inside
  parallel 500 deep);
* a **parallel** mechanism of P-R-S limbs around a circle (up to 667 limbs,
  2,001 joints: one parallel node of 667 children).

Each run builds the mechanism anew (not timed), empties the decomposition's
cache, and times :func:`mobility.analyze`: the whole first analysis (joint
table, decomposition, joint twists, screw systems).  Reported per size: the
median over ``runs`` (wall time, ``time.perf_counter``) with the
interquartile range, and the baseline measured in the same run, building
the :class:`~mobility.Mechanism` itself (its validation is linear in the
joints), as a ratio.  The growth exponent is the least-squares slope of
log(time) against log(joints) over the four sizes (1 = linear).
Targets: at most 100 ms at the largest size of each family, exponent about 1.

With ``--busy``, a 100-joint chain (loaded once) is also analysed while two
other processes keep both cores busy, against the same analyses on a quiet
machine in the same run: small matrices must not wait for BLAS threads (the
analysis forms no matrix larger than 6 x n, so none is threaded).
"""

from __future__ import annotations

import argparse
import gc
import subprocess
import os
import statistics
import sys
import time
from typing import Callable

import numpy as np

import mobility
from mobility.core import topology
from mobility.core.model import Mechanism

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), os.pardir, "tests"))
from builders import prs_limbs, serial_chain, triangle_ladder  # noqa: E402  (the families tests/test_large.py checks)
from _stats import quartiles  # noqa: E402  (benchmarks/, the script's folder)

FAMILIES: dict[str, tuple[Callable[[int], Mechanism], int, str]] = {
    "chain": (serial_chain, 2000, "joints"),
    "ladder": (triangle_ladder, 500, "loops"),
    "parallel": (prs_limbs, 667, "limbs"),
}


def first_analysis(build: Callable[[int], Mechanism], size: int) -> tuple[float, float, int]:
    """Seconds to build the model and to analyse it the first time, and its joint count."""
    topology._decompose.cache_clear()
    gc.collect()
    start = time.perf_counter()
    m = build(size)
    built = time.perf_counter()
    mobility.analyze(m)
    done = time.perf_counter()
    return built - start, done - built, len(m.joints)


def analyses_of_a_chain(runs: int) -> list[float]:
    m = serial_chain(100)
    mobility.analyze(m)
    times = []
    for _ in range(runs):
        start = time.perf_counter()
        for _ in range(100):
            mobility.analyze(m)
        times.append((time.perf_counter() - start) / 100)
    return times


def busy_and_quiet(runs: int) -> tuple[list[float], list[float]]:
    """Analyses of a 100-joint chain with both cores kept busy by two other processes, and without."""
    quiet = analyses_of_a_chain(runs)
    spin = "import time\nend = time.time() + 60\nwhile time.time() < end: pass"
    hogs = [subprocess.Popen([sys.executable, "-c", spin]) for _ in range(os.cpu_count() or 2)]
    try:
        time.sleep(0.5)
        busy = analyses_of_a_chain(runs)
    finally:
        for p in hogs:
            p.kill()
            p.wait()
    return quiet, busy


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--runs", type=int, default=7)
    parser.add_argument("--markdown", action="store_true", help="print a Markdown table")
    parser.add_argument("--busy", action="store_true", help="also time a 100-joint chain with both cores kept busy")
    args = parser.parse_args()
    first_analysis(triangle_ladder, 10)  # warm up imports and caches of code
    rows, slopes = [], {}
    for family, (build, largest, unit) in FAMILIES.items():
        sizes = [largest // 8, largest // 4, largest // 2, largest]
        medians = []
        for size in sizes:
            runs = [first_analysis(build, size) for _ in range(args.runs)]
            joints = runs[0][2]
            q = quartiles([r[1] for r in runs])
            base = statistics.median(r[0] for r in runs)
            medians.append((joints, q[1]))
            rows.append((family, f"{size} {unit}", joints, q, base))
        x, y = np.log([j for j, _ in medians]), np.log([t for _, t in medians])
        slopes[family] = float(np.polyfit(x, y, 1)[0])
    if args.markdown:
        print("| mechanism | joints | first analysis (ms), median [IQR] | µs per joint | building the model (ms) | analysis / building |")
        print("|---|---:|---:|---:|---:|---:|")
        for family, size, joints, q, base in rows:
            print(f"| {family}, {size} | {joints} | {1e3 * q[1]:.1f} [{1e3 * q[0]:.1f}–{1e3 * q[2]:.1f}] | {1e6 * q[1] / joints:.0f} | {1e3 * base:.1f} | {q[1] / base:.1f}× |")
        print()
        print("Growth exponent (slope of log time against log joints): " + ", ".join(f"{f} {s:.2f}" for f, s in slopes.items()))
    else:
        for family, size, joints, q, base in rows:
            print(f"{family + ', ' + size:26s} {joints:5d} joints  first analysis {1e3 * q[1]:7.1f} ms [{1e3 * q[0]:.1f}-{1e3 * q[2]:.1f}]"
                  f"  {1e6 * q[1] / joints:5.0f} us/joint  model {1e3 * base:6.1f} ms  ratio {q[1] / base:4.1f}")
        print("growth exponents: " + ", ".join(f"{f} {s:.2f}" for f, s in slopes.items()))
    if args.busy:
        quiet, busy = busy_and_quiet(2 * args.runs)
        qq, qb = quartiles(quiet), quartiles(busy)
        print(f"\n100-joint chain, loaded: {1e6 * qq[1]:.0f} µs [{1e6 * qq[0]:.0f}–{1e6 * qq[2]:.0f}] quiet, "
              f"{1e6 * qb[1]:.0f} µs [{1e6 * qb[0]:.0f}–{1e6 * qb[2]:.0f}] with every core busy ({qb[1] / qq[1]:.1f}×)")
    print(f"\n{args.runs} runs per size; Python {sys.version.split()[0]}; {os.cpu_count()} CPUs; load average {os.getloadavg()[0]:.1f}")


if __name__ == "__main__":
    main()
