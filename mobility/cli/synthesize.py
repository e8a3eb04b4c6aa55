"""``mobility synthesize PATTERN``: limbs of R and P joints whose finite motions are a motion pattern.

Type synthesis by finite screws (Sun et al. 2018): every serial chain of one-DOF
joints along the pattern's directions, through its points or generic points,
in every order, is tested; the chains whose set of finite motions equals the
pattern are grouped into limb types (S, U, Rc, P1...).  ``--write DIR`` also
assembles a PKM of each limb type with four 6-DOF limbs and writes it as a
mechanism file.  Exit status 0 when a limb is found, 1 when none is, 2 on bad
input.
"""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

from ..errors import SynthesisError
from ..report.text import fmt_vector
from ..synthesis.synthesis import PATTERNS, SynthesisResult, TABLE_1_2T3R, named_pattern, pkm_document, synthesize

ORDER = 50


def register(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser(
        "synthesize",
        help="type synthesis: limbs of R and P joints whose finite motions are a motion pattern",
        description="Enumerate limbs of R and P joints whose set of finite motions equals PATTERN "
        "(finite screws, Sun et al. 2018).  Patterns: " + ", ".join(PATTERNS) + ".",
    )
    p.add_argument("pattern", help="motion pattern: " + ", ".join(PATTERNS))
    p.add_argument("--joints", type=int, default=None, help="one-DOF joints per limb (default: the pattern's dimension)")
    p.add_argument("--point", default="0,0,0", metavar="X,Y,Z", help="the pattern's point O (default: %(default)s)")
    p.add_argument("--directions", default=None, metavar="X,Y,Z;X,Y,Z", help="the pattern's translation directions, ';'-separated (default: the coordinate axes)")
    p.add_argument("--samples", type=int, default=3, help="random poses per rank decision (default: %(default)d)")
    p.add_argument("--verify", type=int, default=2, help="finite motions of each kept limb fitted by the pattern (default: %(default)d; 0 skips)")
    p.add_argument("--seed", type=int, default=0, help="seed of every random choice (default: %(default)d)")
    p.add_argument("--write", default=None, metavar="DIR", help="assemble a PKM of each limb type with four 6-DOF limbs and write mechanism files there")
    p.add_argument("--other", choices=("UPS", "SPRR"), default="UPS", help="the 6-DOF limbs of --write (default: %(default)s)")
    p.add_argument("--json", action="store_true", help="print one JSON object")
    p.set_defaults(run=run)


def _vector(text: str, what: str) -> tuple[float, float, float]:
    try:
        parts = [float(x) for x in text.split(",")]
    except ValueError:
        raise SynthesisError(f"{what}: expected three comma-separated numbers, got {text!r}") from None
    if len(parts) != 3:
        raise SynthesisError(f"{what}: expected three comma-separated numbers, got {text!r}")
    return (parts[0], parts[1], parts[2])


def run(args: argparse.Namespace) -> int:
    if args.samples < 1 or args.verify < 0:
        print("mobility synthesize: error: --samples must be at least 1 and --verify not negative", file=sys.stderr)
        return 2
    directions = None if args.directions is None else [_vector(d, "--directions") for d in args.directions.split(";")]
    pattern = named_pattern(args.pattern, point=_vector(args.point, "--point"), directions=directions)
    result = synthesize(pattern, joints=args.joints, samples=args.samples, verify_samples=args.verify, seed=args.seed)
    written: list[str] = []
    skipped: list[str] = []
    if args.write:
        folder = Path(args.write)
        folder.mkdir(parents=True, exist_ok=True)
        for s in result.structures:
            try:
                _, text = pkm_document(result, s.name, other=args.other)
            except SynthesisError as exc:
                skipped.append(f"{s.name}: {exc}")
                continue
            path = folder / f"pkm_{s.name.lower()}_4{args.other.lower()}.yaml"
            path.write_text(text, encoding="utf-8")
            written.append(str(path))
    if args.json:
        data = result.to_dict()
        data["written"] = written
        data["skipped"] = skipped
        print(json.dumps(data, indent=2))
    else:
        print(text_report(result))
        if args.write:
            print(f"wrote {len(written)} mechanism files to {args.write}" + (f"; not assembled (singular at the home pose): {len(skipped)}" if skipped else ""))
            for line in skipped:
                print(f"  {line}")
    return 0 if result.structures else 1


def text_report(result: SynthesisResult) -> str:
    """The report printed by ``mobility synthesize``."""
    p = result.pattern
    out = [f"{p.name}: {p.description}", f"  dimension {p.dim}; S_f = " + " △ ".join(f.describe() for f in p.factors)]
    out.append("  directions: " + ", ".join(f"{k} = {fmt_vector(v)}" for k, v in result.directions.items()))
    out.append("  points: " + ", ".join(f"{k} = {fmt_vector(v)}" for k, v in result.points.items() if not k.startswith("g")) + (", g1.. generic" if any(k.startswith("g") for k in result.points) else ""))
    out.append("  candidate joints: " + " ".join(c.label for c in result.alphabet))
    if result.rejected_joints:
        out.append("  rejected alone (their own motion leaves the pattern): " + " ".join(c.label for c in result.rejected_joints))
    out.append(f"  limb types of {result.joints} one-DOF joints whose finite motions are the pattern: {len(result.structures)} ({result.sequences} joint sequences)")
    width = max((len(s.name) for s in result.structures), default=4)
    for s in result.structures:
        mark = "Table 1" if s.in_table_1 else "       "
        out.append(f"    {s.name:<{width}}  {mark}  {len(s.realizations):>3} seq.  " + "; ".join(s.conditions))
    if p.name == "2T3R" and result.joints == 5:
        found = [n for n in TABLE_1_2T3R if any(s.name == n for s in result.structures)]
        out.append(f"  Table 1 of Sun et al. (2018): {len(found)} of {len(TABLE_1_2T3R)} found; further limb types: {sum(1 for s in result.structures if not s.in_table_1)}")
    out.append(f"  search: {result.candidates_tested} rank tests; {result.verified_samples} sampled finite motions fitted by the pattern to round-off; {result.seconds:.1f} s")
    return "\n".join(out)
