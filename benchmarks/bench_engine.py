"""The screw-system engine against its floor: bare stacked numpy SVDs of the same shapes, measured in the same run.

Run:  python benchmarks/bench_engine.py [--poses 1 8192 100000] [--repeat 5] [--markdown]

Mechanism: the 3-PRS head (``mechanisms/3prs.yaml``) at its file pose, the
pose repeated ``N`` times.  Rows, for each ``N``:

* **engine**: :func:`mobility.core.screw_systems.analyse_poses` on the
  stack of joint twists: the three limbs' twist systems (one stacked SVD of
  ``3N`` matrices 6 x 5), the platform's (``N`` matrices 6 x 3 of the limbs'
  constraint wrenches), the rotational freedoms (``N`` matrices 3 x 3, values
  only), every rank decision, margin, count and pattern;
* **bare SVDs** (the floor): the same three :func:`numpy.linalg.svd` calls
  on arrays of the same shapes, prepared beforehand, and nothing else.

The ratio engine / bare is what the engine adds to LAPACK: its bookkeeping
(ranks, margins, reciprocal systems, counts) and numpy's per-call overhead.
With one pose it is overhead against overhead; with thousands it tells how
close the engine runs to the arithmetic.  Times are CPU time of this process
(``time.process_time``): the median over ``--repeat`` runs of the mean of
enough calls to last about 0.2 s.
"""

from __future__ import annotations

import argparse
import statistics
import time
from pathlib import Path

import numpy as np

import mobility
from mobility.core.joint_screws import joint_screws
from mobility.core.screw_systems import analyse_poses
from mobility.core.topology import decompose
from _stats import quartiles, run_times

ROOT = Path(__file__).resolve().parent.parent


def per_call(fn, repeat: int) -> list[float]:
    """The mean CPU time of one call in each of ``repeat`` runs (calls enough for about 0.2 s a run)."""
    start = time.process_time()
    fn()
    return run_times(fn, max(1, int(0.2 / max(time.process_time() - start, 1e-6))), repeat)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--poses", type=int, nargs="+", default=[1, 8192, 100_000])
    parser.add_argument("--repeat", type=int, default=5)
    parser.add_argument("--markdown", action="store_true")
    args = parser.parse_args()

    m = mobility.load(ROOT / "mechanisms" / "3prs.yaml")
    topology = decompose(m)
    screws = joint_screws(m)
    rows = []
    for n in args.poses:
        twists = np.ascontiguousarray(np.broadcast_to(screws.twists, (n, *screws.twists.shape)))
        answers = analyse_poses(topology, twists, screws.offsets)
        assert answers.dof.tolist() == [3] * n
        limbs = np.concatenate([twists[:, :, :5]] * 3)  # the shapes the engine decomposes
        platform = np.ascontiguousarray(np.concatenate([c.wrenches for c in answers.root.children], axis=2))
        directions = np.ascontiguousarray(answers.root.basis[:, :3])

        def bare() -> None:
            np.linalg.svd(limbs, full_matrices=True)
            np.linalg.svd(platform, full_matrices=True)
            np.linalg.svd(directions, compute_uv=False)

        engine = per_call(lambda: analyse_poses(topology, twists, screws.offsets), args.repeat)
        floor = per_call(bare, args.repeat)
        ratios = [e / f for e, f in zip(engine, floor)]
        rows.append((n, statistics.median(engine), quartiles(engine), statistics.median(floor), statistics.median(ratios), ratios))

    def shown(seconds: float) -> str:
        return f"{seconds * 1e6:.0f} µs" if seconds < 1e-3 else f"{seconds * 1e3:.1f} ms"

    if args.markdown:
        print("| poses | engine | bare stacked SVDs | engine / bare |")
        print("|---|---|---|---|")
        for n, e, _, f, r, runs in rows:
            print(f"| {n:,} | {shown(e)} | {shown(f)} | {r:.2f}× (runs: {', '.join(f'{x:.2f}' for x in runs)}) |")
        return
    for n, e, (q1, _, q3), f, r, runs in rows:
        print(f"{n:>7,} poses: engine {shown(e)} (IQR {shown(q1)}-{shown(q3)}), bare SVDs {shown(f)}, ratio {r:.2f} (runs: {', '.join(f'{x:.2f}' for x in runs)})")


if __name__ == "__main__":
    main()
