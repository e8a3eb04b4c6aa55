"""How long ``mobility.load`` takes, against YAML loading measured in the same run.

Run:  python benchmarks/bench_load.py [--number N] [--repeat R] [--markdown] [FILE...]

For each file (default: ``mechanisms/3prs.yaml`` and the largest bundled
file) it times

* ``load``: :func:`mobility.load`, the whole route from the file to a
  :class:`~mobility.core.model.Mechanism` (YAML with the line of every key,
  the limits, expressions, limb patterns, the model's checks);
* ``load, cold``: the same with the cache of compiled expressions emptied
  before each call (what the first load of a file pays);
* ``parse_yaml``: the YAML step alone (values and lines, limits checked);
* ``C yaml.load``: ``yaml.load(text, Loader=yaml.CSafeLoader)``, plain values
  without lines from libyaml, the baseline of the ratios;
* ``pure-Python yaml.load``: ``yaml.load(text, Loader=yaml.SafeLoader)``,
  the YAML route the reader used before it built documents from libyaml's
  events.

Times are CPU time of this process (``time.process_time``): for each of
``repeat`` runs the mean of ``number`` calls, then the median over the runs.
Ratios are against the C loader measured in the same run, so they hold across
machines better than the times.
"""

from __future__ import annotations

import argparse
from pathlib import Path

import yaml

import mobility
from mobility.io.expressions import compile_expression
from mobility.io.yaml_source import parse_yaml
from _stats import median_time

ROOT = Path(__file__).resolve().parent.parent


def measure(path: Path, number: int, repeat: int) -> dict[str, float]:
    """The times of one file, in seconds."""
    text = path.read_text(encoding="utf-8")

    def cold() -> object:
        compile_expression.cache_clear()
        return mobility.load(path)

    return {
        "load": median_time(lambda: mobility.load(path), number, repeat),
        "cold": median_time(cold, number, repeat),
        "parse": median_time(lambda: parse_yaml(text, str(path)), number, repeat),
        "c_yaml": median_time(lambda: yaml.load(text, Loader=yaml.CSafeLoader), number, repeat),
        "py_yaml": median_time(lambda: yaml.load(text, Loader=yaml.SafeLoader), max(1, number // 4), repeat),
    }


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--number", type=int, default=200)
    parser.add_argument("--repeat", type=int, default=9)
    parser.add_argument("--markdown", action="store_true", help="print a Markdown table")
    parser.add_argument("files", nargs="*", help="mechanism files (default: mechanisms/3prs.yaml and the largest bundled file)")
    args = parser.parse_args()
    bundled = sorted((ROOT / "mechanisms").glob("*.yaml"), key=lambda p: p.stat().st_size)
    files = [Path(f) for f in args.files] or [ROOT / "mechanisms" / "3prs.yaml", bundled[-1]]
    rows = []
    for path in files:
        m = mobility.load(path)
        t = measure(path, args.number, args.repeat)
        rows.append((path.name, len(m.joints), t))
    if args.markdown:
        print("| file | joints | load (µs) | load, cold (µs) | parse_yaml (µs) | C yaml.load (µs) | pure-Python yaml.load (µs) | load / C yaml.load | pure-Python yaml.load / load |")
        print("|---|---:|---:|---:|---:|---:|---:|---:|---:|")
        for name, joints, t in rows:
            print(
                f"| {name} | {joints} | {t['load'] * 1e6:.0f} | {t['cold'] * 1e6:.0f} | {t['parse'] * 1e6:.0f} | {t['c_yaml'] * 1e6:.0f} "
                f"| {t['py_yaml'] * 1e6:.0f} | {t['load'] / t['c_yaml']:.1f}× | {t['py_yaml'] / t['load']:.1f}× |"
            )
    else:
        print(f"{'file':28s} {'joints':>6s} {'load µs':>8s} {'cold µs':>8s} {'parse µs':>9s} {'C yaml µs':>10s} {'py yaml µs':>11s} {'load/C':>7s} {'py/load':>8s}")
        for name, joints, t in rows:
            print(
                f"{name:28s} {joints:6d} {t['load'] * 1e6:8.0f} {t['cold'] * 1e6:8.0f} {t['parse'] * 1e6:9.0f} {t['c_yaml'] * 1e6:10.0f} "
                f"{t['py_yaml'] * 1e6:11.0f} {t['load'] / t['c_yaml']:6.1f}x {t['py_yaml'] / t['load']:7.1f}x"
            )


if __name__ == "__main__":
    main()
