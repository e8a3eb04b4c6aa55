"""``mobility view FILE -o FILE.html``: an interactive 3D view of the mechanism, its freedoms and constraints.

``--samples N`` or ``--vary`` (as ``mobility sweep``) add poses, on a slider.
"""

from __future__ import annotations

import argparse
from dataclasses import replace

from ..core.analysis import analyze
from ..core.model import Mechanism
from ..errors import RequestError, counted, one_line
from ..view import MAX_POSES, ViewFrame, mechanism_view, poses_view, sweep_view
from ..view.page import require_plotly
from ..io.limits import require_size, require_work
from ._options import (add_max_poses_option, add_mechanism_file, add_pose_sampler_options, add_tolerance_option, max_poses_from, read_with_notes,
                       require_new_output, require_option_for, sampled_poses, tolerance_from)

ORDER = 31

PAGE_SUFFIXES = (".html", ".htm")
"""The endings of a page name that ``-o`` accepts, compared in lower case (``page.HTML`` too)."""


def register(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser("view",
                       help="write an interactive 3D view (one HTML page, works offline) of the mechanism with its freedoms and constraints",
                       description="Write one self-contained HTML page with the mechanism in 3D: links, joints by type, the end effector, "
                       "its freedoms (translation arrows, rotation axes with their pitch) and constraint wrenches (force lines, couples), "
                       "each layer switchable, hover text with each screw's numbers. Rotate, zoom and pan with the mouse. "
                       "Needs plotly (pip install 'mechanism-mobility[view]').")
    add_mechanism_file(p)
    p.add_argument("-o", "--output", required=True, help="page to write (a name ending in .html or .htm, in any case)")
    poses = p.add_mutually_exclusive_group()
    poses.add_argument("--vary", action="append", default=[], metavar="NAME=START:STOP:COUNT",
                       help="show the poses of a sweep, as for `mobility sweep` (repeat for a grid), with a slider; "
                       f"it draws at most {counted(MAX_POSES, 'pose')}, evenly spaced, every singular one kept")
    add_max_poses_option(p, what="with --vary: refuse a grid of more poses, as `mobility sweep` does")
    add_pose_sampler_options(p, samples_help="also show N poses reached by moving the mechanism, with a slider", samples_group=poses, most=MAX_POSES - 1)
    add_tolerance_option(p)
    p.set_defaults(run=run)


def _poses_shown(args: argparse.Namespace, mechanism: Mechanism, max_poses: int) -> tuple[int, str]:
    """The poses that ``--samples`` or ``--vary`` moves and analyses one by one (a view of a grid draws at most :data:`MAX_POSES` of them), and the option as given."""
    if not args.vary:
        return args.samples, f"--samples {args.samples}"
    from ..sweeps import plan_grid  # the sweeps: only for --vary

    size = plan_grid(mechanism, args.vary, max_poses=max_poses).size
    return min(size, MAX_POSES), f"--vary (a grid of {counted(size, 'pose', grouped=True)}, {min(size, MAX_POSES):,} of them drawn)"


def run(args: argparse.Namespace) -> int:
    tol = tolerance_from(args)
    if not args.output.lower().endswith(PAGE_SUFFIXES):
        raise RequestError(f"{args.output}: expected a page name ending in .html or .htm (in any case)")
    require_new_output(args.output, "-o", args.file)
    max_poses = max_poses_from(args)
    require_option_for(args, "max_poses", "--max-poses", "--vary", bool(args.vary), "it bounds the grid of the poses a --vary sweep shows")
    for dest in ("step", "seed"):
        require_option_for(args, dest, f"--{dest}", "--samples", bool(args.samples), "it sets how the sampled poses are reached")
    if args.samples >= MAX_POSES:  # the file's pose and the sampled ones, before any work
        raise RequestError(f"a view shows at most {counted(MAX_POSES, 'pose')}, the file's and {MAX_POSES - 1} sampled; ask for fewer", argument=f"--samples {args.samples}")
    require_plotly()  # before any work
    read = read_with_notes(args, outputs=((args.output, "-o"),))
    mechanism = read.mechanism
    tol = tolerance_from(args, mechanism.precision)
    if args.vary or args.samples:
        require_size(mechanism, "max_moving_joints", "--vary" if args.vary else "--samples", args.file)
        require_work(mechanism, *_poses_shown(args, mechanism, max_poses), args.file)
    poses = sampled_poses(args, mechanism)
    result = analyze(mechanism, tol=tol)
    if args.vary:
        from ..sweeps import sweep

        view = sweep_view(sweep(mechanism, args.vary, tol=tol, max_poses=max_poses))
    elif args.samples:
        frames = [ViewFrame(mechanism, result, "as in the file")]
        frames += [ViewFrame(p, analyze(p, tol=tol), f"sampled pose {k + 1}") for k, p in enumerate(poses)]
        view = poses_view(frames)
    else:
        view = mechanism_view(mechanism, result)
    if read.closures:  # a robot file's closed loops: the advice of mobility analyze, in the page's header
        from ..core.closures import closure_advice
        from ..report.closures import closures_report

        view = replace(view, notes=view.notes + tuple(closures_report(closure_advice(mechanism, read.closures, tol=tol)).splitlines()))
    path = view.write_html(args.output)
    pose_count = f", {counted(len(view.frames), 'pose')}" if len(view.frames) > 1 else ""
    print(one_line(f"wrote {path}: {result.name}, end effector {result.dof} DOF ({result.pattern}), mobility {result.mobility}{pose_count}"))
    return 0
