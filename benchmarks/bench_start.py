"""Start-up: ``mobility analyze`` as a whole process, against ``python -c "import numpy"`` in the same run.

Run:  python benchmarks/bench_start.py [--runs N] [--markdown]

Each command is run ``runs`` times, interleaved (so a busy spell of a shared
machine hits both), as a fresh process; for each the wall time and the CPU
time (user + system, from ``resource.getrusage`` of the children) are
recorded.  Reported: the median, and the spread as the interquartile range;
the ratio is of medians, against the baseline measured in the same run.
Target: ``mobility analyze mechanisms/3prs.yaml`` at most 2x the baseline.

The commands:

* ``python -c pass`` -- the interpreter alone;
* ``python -c "import numpy"`` -- the baseline;
* ``python -c "import mobility"`` -- the library (numpy, PyYAML and the core);
* ``mobility analyze mechanisms/3prs.yaml`` -- the whole command, through the
  installed console script when there is one (else ``python -m mobility``);
* ``mobility check mechanisms`` is timed by ``bench_check.py``.
"""

from __future__ import annotations

import argparse
import os
import resource
import shutil
import statistics
import subprocess
import sys
import time
from pathlib import Path
from _stats import quartiles

ROOT = Path(__file__).resolve().parent.parent


def commands() -> dict[str, list[str]]:
    script = shutil.which("mobility", path=str(Path(sys.executable).parent)) or shutil.which("mobility")
    analyze = [script] if script else [sys.executable, "-m", "mobility"]
    return {
        "python -c pass": [sys.executable, "-c", "pass"],
        'python -c "import numpy"': [sys.executable, "-c", "import numpy"],
        'python -c "import mobility"': [sys.executable, "-c", "import mobility"],
        "mobility analyze mechanisms/3prs.yaml": analyze + ["analyze", "mechanisms/3prs.yaml"],
    }


def run_once(argv: list[str]) -> tuple[float, float]:
    """Wall and CPU seconds of one run of ``argv`` (output discarded; a failure stops the benchmark)."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    start = time.perf_counter()
    subprocess.run(argv, cwd=ROOT, check=True, stdout=subprocess.DEVNULL, env=dict(os.environ, PYTHONDONTWRITEBYTECODE="0"))
    wall = time.perf_counter() - start
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return wall, (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--runs", type=int, default=15)
    parser.add_argument("--markdown", action="store_true", help="print a Markdown table")
    args = parser.parse_args()
    cmds = commands()
    for argv in cmds.values():  # warm the file cache and the bytecode
        run_once(argv)
    walls: dict[str, list[float]] = {name: [] for name in cmds}
    cpus: dict[str, list[float]] = {name: [] for name in cmds}
    for _ in range(args.runs):
        for name, argv in cmds.items():
            wall, cpu = run_once(argv)
            walls[name].append(wall)
            cpus[name].append(cpu)
    base = 'python -c "import numpy"'
    base_wall, base_cpu = statistics.median(walls[base]), statistics.median(cpus[base])
    rows = []
    for name in cmds:
        wq, cq = quartiles(walls[name]), quartiles(cpus[name])
        rows.append((name, wq, cq, wq[1] / base_wall, cq[1] / base_cpu))
    if args.markdown:
        print("| command | wall (ms), median [IQR] | CPU (ms), median [IQR] | wall / numpy | CPU / numpy |")
        print("|---|---:|---:|---:|---:|")
        for name, wq, cq, rw, rc in rows:
            print(f"| `{name}` | {1e3 * wq[1]:.0f} [{1e3 * wq[0]:.0f}–{1e3 * wq[2]:.0f}] | {1e3 * cq[1]:.0f} [{1e3 * cq[0]:.0f}–{1e3 * cq[2]:.0f}] | {rw:.2f}× | {rc:.2f}× |")
    else:
        for name, wq, cq, rw, rc in rows:
            print(f"{name:42s} wall {1e3 * wq[1]:6.0f} ms [{1e3 * wq[0]:.0f}-{1e3 * wq[2]:.0f}]  cpu {1e3 * cq[1]:6.0f} ms [{1e3 * cq[0]:.0f}-{1e3 * cq[2]:.0f}]  "
                  f"wall/numpy {rw:.2f}  cpu/numpy {rc:.2f}")
    print(f"\n{args.runs} interleaved runs each; Python {sys.version.split()[0]}; {os.cpu_count()} CPUs; load average {os.getloadavg()[0]:.1f}")


if __name__ == "__main__":
    main()
