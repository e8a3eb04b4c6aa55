"""``mobility check mechanisms`` as a whole process, and where its time goes.

Run:  python benchmarks/bench_check.py [--runs N] [--markdown]

Part 1 runs ``mobility check mechanisms`` (every file of ``mechanisms/``,
eleven of them with full-cycle expectations that move the mechanism) and the
baseline ``python -c "import numpy"`` as fresh processes, ``runs`` times each,
interleaved; reported: the median wall time with the interquartile range,
and the ratio of medians.  Target (issue 30): at most 10 times the numpy
import.  The processes run as the environment says: where
``PYTHONDONTWRITEBYTECODE`` is set (the development machine), every module of
the package is compiled from its source in every run, about 0.1 s that an
installed package (with its bytecode) does not spend; the last line says
which.

Part 2 times, in this process and in the order a check meets them, the
imports (the package; networkx, which the spanning trees of the full-cycle
analyses and of the loop closure need; the check imports no scipy), loading
the files, analysing them, and the full-cycle analyses
(:func:`mobility.finite_mobility`) of the eleven files that expect them, with
their Newton steps (each move's own, summed; every move of a run is
re-closed in one Newton solve on the stack), and the actuation verdicts of
the files that expect one.
"""

from __future__ import annotations

import argparse
import os
import shutil
import subprocess
import sys
import time
from pathlib import Path
from _stats import quartiles

ROOT = Path(__file__).resolve().parent.parent
FINITE_KEYS = ("full_cycle_dof", "full_cycle_mobility", "finite_verdict")


def wall(argv: list[str]) -> float:
    start = time.perf_counter()
    subprocess.run(argv, cwd=ROOT, stdout=subprocess.DEVNULL, check=False)
    return time.perf_counter() - start


def whole_process(runs: int) -> list[tuple[str, tuple[float, float, float]]]:
    script = shutil.which("mobility", path=str(Path(sys.executable).parent)) or shutil.which("mobility")
    check = ([script] if script else [sys.executable, "-m", "mobility"]) + ["check", "mechanisms"]
    commands = {'python -c "import numpy"': [sys.executable, "-c", "import numpy"], "mobility check mechanisms": check}
    for argv in commands.values():
        wall(argv)  # warm the file cache
    times: dict[str, list[float]] = {name: [] for name in commands}
    for _ in range(runs):
        for name, argv in commands.items():
            times[name].append(wall(argv))
    return [(name, quartiles(t)) for name, t in times.items()]


def stages() -> list[tuple[str, float]]:
    """Seconds of each stage of a check, in this (fresh) process."""
    out = []
    start = time.perf_counter()
    import mobility
    from mobility.testing.check import check_paths  # noqa: F401

    out.append(("import mobility", time.perf_counter() - start))
    for name in ("networkx",):
        start = time.perf_counter()
        __import__(name)
        out.append((f"import {name}", time.perf_counter() - start))
    files = sorted((ROOT / "mechanisms").glob("*.yaml"))
    start = time.perf_counter()
    mechanisms = [mobility.load(f) for f in files]
    out.append((f"load {len(files)} files", time.perf_counter() - start))
    start = time.perf_counter()
    for m in mechanisms:
        mobility.analyze(m)
    out.append((f"analyze {len(files)} files", time.perf_counter() - start))
    from mobility.finite import finite_mobility

    moving = [m for m in mechanisms if m.expected is not None and any(k in dict(m.expected.items()) for k in FINITE_KEYS)]
    start = time.perf_counter()
    steps = sum(sum(p.iterations[i] for p in f.probes for i in range(len(p.iterations))) for f in (finite_mobility(m) for m in moving))
    out.append((f"full-cycle analyses of {len(moving)} files ({steps} Newton steps of the moves from the given poses)", time.perf_counter() - start))
    from mobility.actuation import check_actuation

    driven = [m for m in mechanisms if m.expected is not None and "actuation" in dict(m.expected.items())]
    start = time.perf_counter()
    for m in driven:
        check_actuation(m)
    out.append((f"actuation verdicts of {len(driven)} files", time.perf_counter() - start))
    if "scipy" in sys.modules:
        out.append(("(scipy was imported: a check should not need it)", float("nan")))
    return out


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--runs", type=int, default=9)
    parser.add_argument("--markdown", action="store_true", help="print Markdown tables")
    args = parser.parse_args()
    rows = whole_process(args.runs)
    base = rows[0][1][1]
    parts = stages()
    if args.markdown:
        print("| command | wall (s), median [IQR] | / numpy import |")
        print("|---|---:|---:|")
        for name, q in rows:
            print(f"| `{name}` | {q[1]:.2f} [{q[0]:.2f}–{q[2]:.2f}] | {q[1] / base:.1f}× |")
        print()
        print("| stage (in one process) | s |")
        print("|---|---:|")
        for name, seconds in parts:
            print(f"| {name} | {seconds:.3f} |")
    else:
        for name, q in rows:
            print(f"{name:30s} wall {q[1]:6.2f} s [{q[0]:.2f}-{q[2]:.2f}]  x{q[1] / base:.1f} numpy import")
        for name, seconds in parts:
            print(f"  {name:80s} {seconds:6.3f} s")
    bytecode = "off (PYTHONDONTWRITEBYTECODE)" if os.environ.get("PYTHONDONTWRITEBYTECODE") else "on"
    print(f"\n{args.runs} interleaved runs; Python {sys.version.split()[0]}; {os.cpu_count()} CPUs; load average {os.getloadavg()[0]:.1f}; bytecode caches {bytecode}")


if __name__ == "__main__":
    main()
