"""``mobility plot FILE -o out.png``: a picture of the mechanism and its freedoms, or of its joint graph."""

from __future__ import annotations

import argparse

from ..core.analysis import analyze
from ..errors import MechanismFileError, PlotFormatError, RequestError, one_line
from ..report.plotting.backend import DPI_RANGE
from ._options import add_mechanism_file, integer_option, add_tolerance_option, read_with_notes, require_new_output, tolerance_from

ORDER = 30


def register(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser("plot",
                       help="draw the mechanism with its end effector's freedoms (or its joint graph) to PNG, SVG or PDF",
                       description="Draw the mechanism at its pose with the end effector's freedoms: arrows for translations, "
                       "axis lines with a rotation mark for rotations (pitch written where non-zero). Needs matplotlib "
                       "(pip install 'mechanism-mobility[plot]').")
    add_mechanism_file(p)
    p.add_argument("-o", "--output", required=True, help="picture to write; the type follows the suffix: .png, .svg or .pdf")
    p.add_argument("--constraints", action="store_true", help="also draw the constraint wrenches (force lines, couples)")
    p.add_argument("--graph", action="store_true", help="draw the joint graph and its series/parallel tree instead")
    p.add_argument("--views", type=integer_option, default=2, choices=(1, 2, 3), help="number of viewpoints (default: %(default)s)")
    p.add_argument("--no-labels", action="store_true", help="leave out the joint names")
    p.add_argument("--dpi", type=integer_option, default=150, help=f"resolution of a PNG, {DPI_RANGE[0]} to {DPI_RANGE[1]} dots per inch (default: %(default)s)")
    add_tolerance_option(p)
    p.set_defaults(run=run)


def _is_flexure(path: str) -> bool:
    """Whether ``path`` holds a flexure document (read again, within the size limit, only to explain a load error)."""
    from ..flexure import is_flexure_document
    from ..io.yaml_source import parse_yaml, read_text

    try:
        data, _ = parse_yaml(read_text(path), path)
    except MechanismFileError:
        return False
    return is_flexure_document(data)


def run(args: argparse.Namespace) -> int:
    from ..report.plotting import picture_path, plot_graph, plot_mechanism, save_figure

    tol = tolerance_from(args)
    if not DPI_RANGE[0] <= args.dpi <= DPI_RANGE[1]:
        raise RequestError(f"--dpi must lie in [{DPI_RANGE[0]}, {DPI_RANGE[1]}], got {args.dpi}")
    picture_path(args.output)  # before any work
    require_new_output(args.output, "-o", args.file)
    given: frozenset[str] = getattr(args, "given_options", frozenset())  # the options typed (mobility.cli.options_given)
    drawn = [option for option, on in (("--constraints", args.constraints), ("--views", "views" in given), ("--no-labels", args.no_labels)) if on]
    if args.graph and drawn:
        raise RequestError(f"{' and '.join(drawn)} draw{'s' if len(drawn) == 1 else ''} on the mechanism, not on the --graph picture")
    try:
        mechanism = read_with_notes(args, outputs=((args.output, "-o"),)).mechanism
    except MechanismFileError:
        if _is_flexure(args.file):
            raise PlotFormatError("a flexure document (bodies joined by elements); `mobility plot` draws mechanisms with joints, see `mobility actuation` for flexures",
                                  argument=args.file) from None
        raise
    tol = tolerance_from(args, mechanism.precision)
    result = analyze(mechanism, tol=tol)
    if args.graph:
        fig = plot_graph(mechanism, result, tol=tol)
    else:
        fig = plot_mechanism(mechanism, result, constraints=args.constraints, views=args.views, labels=not args.no_labels, tol=tol)
    try:
        path = save_figure(fig, args.output, dpi=args.dpi)
    except OSError as exc:
        raise MechanismFileError("--output", f"cannot write the file ({exc.strerror or exc})", file=args.output) from None
    print(one_line(f"wrote {path}: {result.name}, end effector {result.dof} DOF ({result.pattern})"))
    return 0
