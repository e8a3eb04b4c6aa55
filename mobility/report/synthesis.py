"""Reports of a type synthesis (:class:`~mobility.synthesis.SynthesisResult`) printed by ``mobility synthesize``: text and JSON.

Examples
--------
>>> from mobility.synthesis import synthesize
>>> result = synthesize("3R", verify_samples=1)
>>> print(synthesis_text(result).splitlines()[0])
3R: rotations about the fixed point O
>>> print(written_files_text("out", ["out/pkm_s_4ups.yaml"], []))
wrote 1 mechanism files to out
"""

from __future__ import annotations

import json
from typing import Sequence

from ..synthesis import TABLE_1_2T3R, SynthesisResult
from .text import fmt_vector

__all__ = ["synthesis_text", "written_files_text", "synthesis_json"]


def synthesis_text(result: SynthesisResult) -> str:
    """The report printed by ``mobility synthesize``: the pattern, the candidates, the limb types found."""
    p = result.pattern
    out = [f"{p.name}: {p.description}", f"  dimension {p.dim}; S_f = " + " △ ".join(f.describe() for f in p.factors)]
    out.append("  directions: " + ", ".join(f"{k} = {fmt_vector(v)}" for k, v in result.directions.items()))
    out.append("  points: " + ", ".join(f"{k} = {fmt_vector(v)}" for k, v in result.points.items() if not k.startswith("g")) + (", g1.. generic" if any(k.startswith("g") for k in result.points) else ""))
    out.append("  candidate joints: " + " ".join(c.label for c in result.alphabet))
    if result.rejected_joints:
        out.append("  rejected alone (their own motion leaves the pattern): " + " ".join(c.label for c in result.rejected_joints))
    if result.joints < p.dim:  # chains too short to fill the pattern: parts of limbs
        out.append(f"  chains of {result.joints} one-DOF joints whose finite motions lie in the pattern (fewer joints than its dimension {p.dim}: "
                   f"parts of limbs, not limbs): {len(result.structures)} ({result.sequences} joint sequences)")
    else:
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


def written_files_text(folder: str, written: Sequence[str], skipped: Sequence[str]) -> str:
    """What ``mobility synthesize --write`` adds: how many files were written, and the limb types skipped."""
    lines = [f"wrote {len(written)} mechanism files to {folder}" + (f"; not assembled (singular at the home pose): {len(skipped)}" if skipped else "")]
    lines += [f"  {line}" for line in skipped]
    return "\n".join(lines)


def synthesis_json(result: SynthesisResult, written: Sequence[str] = (), skipped: Sequence[str] = ()) -> str:
    """The result as one JSON object (``mobility synthesize --json``), with the files written and skipped."""
    return json.dumps(result.to_dict() | {"written": list(written), "skipped": list(skipped)}, indent=2)
