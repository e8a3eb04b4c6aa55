"""``mobility actuation FILE``: which joints (or a flexure document's linear actuators) may drive a mechanism (docs/actuation.md)."""

from __future__ import annotations

import argparse

from ..actuation import ENUMERATION_MODES, ActuationCheck, Enumeration, check_actuation, check_over_poses, enumerate_actuations
from ..core.model import Mechanism
from ..core.tolerance import Tolerance
from ..errors import RequestError
from ..flexure import FlexureMechanism, check_force_lines, enumerate_force_lines, flexure_spaces, is_flexure_document, loads_flexure
from ..io.loader import is_robot_description
from ..io.yaml_source import parse_yaml, read_text
from ..report.actuation import actuation_json, actuation_text, enumeration_json, enumeration_text, flexure_json, flexure_text
from ..io.limits import require_size, require_work
from ._options import (MECHANISM_FILE_HELP, OPTION_SPELLING, add_mechanism_file, add_pose_sampler_options, add_tolerance_option, integer_option,
                       names_from, number_option, require_option_for, require_sampler_options, read_mechanism, read_with_notes, robot_options_from,
                       sampled_poses, tolerance_from)

ORDER = 30
EXIT_STATUS = "0 the chosen inputs are valid (with --enumerate: at least one combination is), 1 otherwise, 2 bad input (one line on standard error)"


def register(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser("actuation",
                       help="which joints (or linear actuators) may drive the mechanism: actuation wrenches and verdicts",
                       description="Actuation spaces (Li, Shan, Yu, Ke 2021): a choice of inputs is valid when its actuation wrenches "
                       "and the constraint wrenches together span six dimensions.")
    add_mechanism_file(p, file_help=MECHANISM_FILE_HELP + ", or flexure document (YAML)")
    p.add_argument("--enumerate", action="store_true", help="check every combination of inputs, grouped by type and ranked")
    p.add_argument("--mode", choices=ENUMERATION_MODES, default=None, help="enumeration: one joint per limb (default) or any K joints")
    p.add_argument("--k", type=integer_option, default=None, help="inputs per combination with --mode any (default: the DOF)")
    p.add_argument("--inputs", default=None, help="comma-separated joint (or actuator) names to check instead of those marked actuated; "
                   "NAME.k names freedom k (from 0, as reported) of a multi-freedom joint")
    p.add_argument("--pose", action="append", default=[], metavar="FILE", help="another pose of the same mechanism, read as FILE is (repeatable)")
    add_pose_sampler_options(p, samples_help="also check N poses reached by moving the mechanism (mobility.core.poses.sample_poses)")
    p.add_argument("--threshold", type=number_option, default=None, help="flexure: relative compliance above which a direction is free (default: the file's, else 0.01)")
    add_tolerance_option(p)
    p.add_argument("--json", action="store_true", help="print one JSON object")
    p.set_defaults(run=run)


def run(args: argparse.Namespace) -> int:
    tol = tolerance_from(args)
    if args.threshold is not None and not (0.0 < args.threshold < 1.0):
        raise RequestError("--threshold must lie between 0 and 1")
    require_sampler_options(args)
    for dest in ("step", "seed"):
        require_option_for(args, dest, f"--{dest}", "--samples", bool(args.samples), "it sets how the sampled poses are reached")
    if args.k is not None and not (0 <= args.k <= 6):
        raise RequestError(f"--k must lie in [0, 6] (inputs per combination, at most the 6 freedoms of a body), got {args.k}")
    if not args.enumerate and (args.mode is not None or args.k is not None):
        raise RequestError("--mode and --k choose the combinations of --enumerate; give --enumerate too (or --inputs to check one choice)")
    if args.enumerate and args.inputs is not None:
        raise RequestError("--inputs checks one choice and --enumerate every combination: give one of them")
    if not is_robot_description(args.file):  # a YAML document: a mechanism or a flexure
        text = read_text(args.file)
        data, _ = parse_yaml(text, args.file)
        if is_flexure_document(data):
            if args.mode is not None:
                raise RequestError(f"--mode chooses how a rigid mechanism's joints are combined (one per limb, or any); the actuators of the flexure document {args.file} are combined as any --k of them")
            if args.pose or args.samples:
                raise RequestError("--pose and --samples apply to rigid mechanisms only (a flexure is analysed at its one pose)")
            given = sorted(robot_options_from(args))
            if given:
                raise RequestError(f"{', '.join(OPTION_SPELLING[k] for k in given)}: options of robot description files (MJCF, URDF), not of the flexure document {args.file}")
            flexure = loads_flexure(text, file=args.file)
            return _run_flexure(args, flexure, names_from(args.inputs, [a.name for a in flexure.actuators]), tol)
    if args.threshold is not None:  # it would be ignored: a rigid mechanism has no compliance
        raise RequestError(f"--threshold applies to flexure documents (their compliance), not to the rigid mechanism {args.file}")
    mechanism = read_with_notes(args).mechanism
    tol = tolerance_from(args, mechanism.precision)
    names = names_from(args.inputs, [j.name for j in mechanism.joints])
    if args.enumerate:
        require_size(mechanism, "max_enumerated_joints", "--enumerate", args.file)
    if args.samples:
        require_size(mechanism, "max_moving_joints", "--samples", args.file)
        require_work(mechanism, args.samples, f"--samples {args.samples}", args.file)
    if args.enumerate:
        poses = [_pose(args, p) for p in args.pose]
        found = enumerate_actuations(mechanism, mode=args.mode or "limb", k=args.k, poses=poses, samples=args.samples, step=args.step, seed=args.seed, tol=tol)
        print(enumeration_json(found) if args.json else enumeration_text(found))
        return 0 if found.valid else 1
    check = check_actuation(mechanism, names, tol=tol)
    extra = check_over_poses(mechanism, names, [_pose(args, p) for p in args.pose], tol=tol) if args.pose else ()
    if args.samples:
        extra = tuple(extra) + check_over_poses(mechanism, names, sampled_poses(args, mechanism), tol=tol)
    checked = list(zip([*args.pose, *(f"sampled pose {i + 1}" for i in range(len(extra) - len(args.pose)))], extra))
    print(actuation_json(check, checked) if args.json else actuation_text(check, checked))
    return 0 if check.valid and all(c.valid for c in extra) else 1


def _pose(args: argparse.Namespace, path: str) -> Mechanism:
    """The mechanism of ``--pose path``, read as FILE is (a YAML pose of a robot description read with options is refused, naming the pose)."""
    given = sorted(robot_options_from(args))
    if given and not is_robot_description(path):
        options = ", ".join(OPTION_SPELLING[k] for k in given)
        raise RequestError(f"--pose {path}: a mechanism file (YAML), while FILE {args.file} is a robot description read with {options}; "
                           "a pose is read as FILE is, with the same options: give the pose as a robot description too")
    return read_mechanism(args, path).mechanism


def _run_flexure(args: argparse.Namespace, mechanism: FlexureMechanism, names: list[str] | None, tol: Tolerance) -> int:
    spaces = flexure_spaces(mechanism, args.threshold, tol=tol)
    answer: ActuationCheck | Enumeration
    if args.enumerate:
        answer = enumerate_force_lines(mechanism, args.k, threshold=args.threshold, tol=tol)
    else:
        answer = check_force_lines(mechanism, names, threshold=args.threshold, tol=tol)
    print(flexure_json(spaces, answer) if args.json else flexure_text(spaces, answer))
    return 0 if answer.valid else 1
