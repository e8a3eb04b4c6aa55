"""Sweep speed: the batched route against the per-pose loop, measured in the same run.

Run:  python benchmarks/bench_sweep.py [--grid 50 50 40] [--repeat 3] [--sample 200] [--workers N] [--markdown]

Mechanism: the 3-PRS head (``mechanisms/3prs.yaml``), its three sliders each
swept over -30..30 mm, a grid of ``50 x 50 x 40 = 100,000`` poses (every one
assembled).  Rows:

* **analysis**: the assembled poses (their joint variables already found)
  analysed: each pose's joint twists in its own normalised coordinates, the
  series/parallel screw systems, DOF, pattern, mobility and margins
  (:func:`mobility.sweeps.analyse_joint_variables` without inputs).  Baseline: for
  ``--sample`` poses of the grid, rebuilding the pose as a mechanism
  (``Kinematics.mechanism_at``) and calling :func:`mobility.analyze`, the
  per-pose loop a user would write;
* **analysis + actuation**: the same with the verdict and conditioning of the
  file's inputs (P1, P2, P3).  Baseline: rebuild, ``analyze`` and
  :func:`mobility.check_actuation` per pose;
* **whole sweep**: :func:`mobility.sweep` from the file (continuation, Newton
  on every pose, analysis, actuation and the transmission indices).  Baseline:
  per pose, re-closing the loops with :meth:`Kinematics.close` from the
  neighbouring pose, rebuilding, ``analyze`` and ``check_actuation``;
* **sweep with indices**: the same whole sweep against itself with
  ``transmission=False`` (no ``iti``, ``oti``, ``lti``, ``cti`` columns), the
  two run in turn (with, without, with, ...) in the same run: the cost of the
  transmission indices (:mod:`mobility.transmission`); the ratios are with
  over without, of the medians (at most 1.5).

Times are medians of ``--repeat`` runs, wall clock and CPU time of the
process (all its threads; the batched runs use ``--workers`` threads,
default all CPUs); a baseline's wall time per pose is the median over runs of
``--sample`` poses, scaled to the grid.  The load average is printed with
the table: on a shared machine the wall times of the batched runs suffer
first (they want every core).  Ratios are
baseline over batched in the same run, so they hold across machines better
than the times; on a machine shared with other work both move.
"""

from __future__ import annotations

import argparse
import os
import statistics
import time
from pathlib import Path

import numpy as np

import mobility
from mobility.core.kinematics import kinematics
from mobility.sweeps import analyse_joint_variables, plan_grid, sweep

ROOT = Path(__file__).resolve().parent.parent


def wall(fn) -> float:
    start = time.perf_counter()
    fn()
    return time.perf_counter() - start


def timed(fn, repeat: int) -> tuple[float, float]:
    """Medians of the wall time and of this process's CPU time (all threads) over ``repeat`` runs."""
    walls, cpus = [], []
    for _ in range(repeat):
        cpu, start = time.process_time(), time.perf_counter()
        fn()
        walls.append(time.perf_counter() - start)
        cpus.append(time.process_time() - cpu)
    return statistics.median(walls), statistics.median(cpus)


def alternated(with_, without, repeat: int) -> tuple[float, float, float, float]:
    """Medians of wall and CPU time of two functions run in turn ``repeat`` times each (the same load on both)."""
    a = [timed(with_, 1) + timed(without, 1) for _ in range(repeat)]
    return tuple(statistics.median(run[k] for run in a) for k in range(4))  # type: ignore[return-value]


def threaded(m: mobility.Mechanism, q: np.ndarray, workers: int, actuated: list[str]) -> None:
    """The analysis of ``q`` cut in one part per thread, as :func:`mobility.sweep` runs it."""
    from concurrent.futures import ThreadPoolExecutor

    parts = np.array_split(q, workers)
    with ThreadPoolExecutor(workers) as pool:
        list(pool.map(lambda part: analyse_joint_variables(m, part, actuated=actuated, transmission=False), parts))


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--grid", type=int, nargs=3, default=(50, 50, 40), metavar=("N1", "N2", "N3"))
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--sample", type=int, default=200, help="poses timed per run of a per-pose baseline")
    parser.add_argument("--workers", type=int, default=os.cpu_count() or 1)
    parser.add_argument("--markdown", action="store_true", help="print only the Markdown table")
    args = parser.parse_args()

    m = mobility.load(ROOT / "mechanisms" / "3prs.yaml")
    n1, n2, n3 = args.grid
    vary = [f"P1=-30:30:{n1}", f"P2=-30:30:{n2}", f"P3=-30:30:{n3}"]
    size = n1 * n2 * n3
    log = (lambda *a: None) if args.markdown else print
    log(f"3-PRS, grid {n1} x {n2} x {n3} = {size:,} poses, {args.workers} worker thread(s), {args.repeat} runs")

    found = {}
    t_whole, c_whole, t_bare, c_bare = alternated(lambda: found.update(result=sweep(m, vary, workers=args.workers)),
                                                  lambda: sweep(m, vary, workers=args.workers, transmission=False), args.repeat)
    result = found["result"]
    assert result.assembled.all() and result.counts() == {(3, "1T2R", 3): size}, "every pose assembled, 3 DOF 1T2R"
    log(f"  whole sweep: {t_whole:.2f} s (CPU {c_whole:.2f} s)")
    log(f"  whole sweep without the transmission indices: {t_bare:.2f} s (CPU {c_bare:.2f} s): with / without {t_whole / t_bare:.2f} (CPU {c_whole / c_bare:.2f})")

    plan = plan_grid(m, vary)
    q = np.array(result.q)
    inputs = [j.name for j in m.joints if j.actuated]
    analyse_joint_variables(m, q[:100])  # build the model once
    t_analysis, c_analysis = timed(lambda: threaded(m, q, args.workers, []), args.repeat)
    t_actuation, c_actuation = timed(lambda: threaded(m, q, args.workers, inputs), args.repeat)
    log(f"  analysis: {t_analysis:.2f} s (CPU {c_analysis:.2f} s), with actuation: {t_actuation:.2f} s (CPU {c_actuation:.2f} s)")

    kin = kinematics(m)
    rng = np.random.default_rng(0)
    neighbour = {}
    flat = np.arange(size).reshape(plan.shape)
    for i in flat[:, :, 1:].ravel():
        neighbour[int(i)] = int(i) - 1
    per_analyze, per_actuation, per_closure = [], [], []
    driven = [kin.variables_of(n).start for n in ("P1", "P2", "P3")]
    lock = np.zeros((3, kin.variable_count))
    lock[range(3), driven] = 1.0
    for _ in range(args.repeat):
        rows = rng.choice(list(neighbour), size=args.sample, replace=False)
        per_analyze.append(wall(lambda: [mobility.analyze(kin.mechanism_at(q[i])) for i in rows]) / args.sample)
        per_actuation.append(wall(lambda: [(mobility.analyze(p), mobility.check_actuation(p, inputs)) for p in (kin.mechanism_at(q[i]) for i in rows)]) / args.sample)

        def closure_loop():
            for i in rows:
                closed = kin.close(q[neighbour[i]], constraints=(lock, q[i][driven]))
                assert closed.converged
                pose = kin.mechanism_at(closed.q)
                mobility.analyze(pose)
                mobility.check_actuation(pose, inputs)

        per_closure.append(wall(closure_loop) / args.sample)
    b_analyze = statistics.median(per_analyze) * size
    b_actuation = statistics.median(per_actuation) * size
    b_closure = statistics.median(per_closure) * size

    rows = [
        ("analysis (DOF, pattern, mobility, margins)", t_analysis, c_analysis, b_analyze, "rebuild + `analyze()` per pose"),
        ("analysis + actuation verdict and conditioning", t_actuation, c_actuation, b_actuation, "rebuild + `analyze()` + `check_actuation()`"),
        ("whole sweep, loop closure included", t_whole, c_whole, b_closure, "`Kinematics.close` + rebuild + `analyze()` + `check_actuation()`"),
    ]
    print(f"| 3-PRS, {size:,} poses ({n1}x{n2}x{n3}), {args.workers} thread(s) | batched (wall) | batched (CPU) | per-pose loop (baseline) | ratio (wall) |")
    print("|---|---:|---:|---|---:|")
    for label, batched, cpu, baseline, how in rows:
        print(f"| {label} | {batched:.2f} s | {cpu:.2f} s ({cpu / size * 1e6:.0f} µs/pose) | {baseline:.0f} s ({baseline / size * 1e3:.2f} ms/pose): {how} | {baseline / batched:.0f}x |")
    print(f"| sweep with transmission indices vs without (same run) | {t_whole:.2f} s | {c_whole:.2f} s | without: {t_bare:.2f} s (CPU {c_bare:.2f} s) | {t_whole / t_bare:.2f}x wall, {c_whole / c_bare:.2f}x CPU (with / without) |")
    print(f"\nload average while it ran (1, 5, 15 min): {', '.join(f'{x:.1f}' for x in os.getloadavg())} on {os.cpu_count()} CPUs")


if __name__ == "__main__":
    main()
