"""``mobility sweep FILE --vary JOINT=START:STOP:COUNT``: mobility, singularity and actuation maps over a grid (docs/sweeps.md)."""

from __future__ import annotations

import argparse
import importlib.util
import sys
from pathlib import Path
from typing import IO, Iterable

from ..errors import MechanismError, RequestError, clipped, counted, one_line
from ..outputs import atomic_output
from ..report.plotting import FORMATS as PICTURE_FORMATS, picture_path, save_figure
from ..report.sweep import sweep_csv_pieces, sweep_json_pieces, sweep_summary
from ..sweeps import DEFAULT_CHUNK_SIZE, MAX_WORKERS, sweep
from ..sweeps.batch_actuation import actuated_inputs
from ..transmission import GOOD_TRANSMISSION
from ..io.limits import require_size
from ._options import add_max_poses_option, add_mechanism_file, integer_option, add_tolerance_option, max_poses_from, names_from, read_with_notes, require_new_output, tolerance_from

ORDER = 35


FORMATS = {"text": lambda result: iter([sweep_summary(result)]), "csv": sweep_csv_pieces, "json": sweep_json_pieces}
"""Output formats: name -> function(result) -> the text in pieces (a table of a million poses is never held whole as text)."""


def register(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser("sweep", help="mobility, singularities and actuation over a grid of poses (joints or end-effector coordinates varied)",
                       description="Vary joints (or the end effector's pose) over a grid, close every loop at every point, and report "
                       "DOF, pattern, mobility, rank margin and, for actuated joints, the actuation verdict and conditioning; "
                       "the summary names the singular poses and where the answer changes.")
    add_mechanism_file(p)
    p.add_argument("--vary", action="append", required=True, metavar="NAME=START:STOP:COUNT",
                   help="a joint (R/H/C: degrees, P: length) or a pose coordinate x, y, z (length), rx, ry, rz (degrees), "
                   "displaced from the file's pose (a joint moves its links[1] relative to links[0], right-handed about its axis); "
                   "COUNT values, both ends included (repeat for a grid)")
    p.add_argument("--inputs", default=None, help="comma-separated joints whose actuation to check (default: those marked actuated); NAME.k names freedom k (from 0) of a multi-freedom joint")
    p.add_argument("--format", choices=sorted(FORMATS), default=None,
                   help="output: a summary, the table as CSV, or JSON (default: what the -o name ends with, .csv or .json, else the summary)")
    p.add_argument("--json", action="store_true", help="same as --format json")
    p.add_argument("-o", "--output", default=None, metavar="FILE", help="write the table to FILE (a line saying so is printed instead; '-': standard output; pictures: --plot)")
    p.add_argument("--plot", default=None, metavar="FILE", help="also draw the sweep (.png, .svg or .pdf): a curve, a map, or slices of a 3-D grid")
    add_max_poses_option(p)
    p.add_argument("--chunk-size", type=integer_option, default=DEFAULT_CHUNK_SIZE, help="poses per chunk of work (default: %(default)d)")
    p.add_argument("--workers", type=integer_option, default=None, help=f"threads in this process, at most {MAX_WORKERS} (default: the number of CPUs)")
    p.add_argument("--scheduler", default=None, metavar="ADDRESS", help="run the chunks on a dask.distributed scheduler (needs mechanism-mobility[dask])")
    bar = p.add_mutually_exclusive_group()
    bar.add_argument("--progress", dest="progress", action="store_true", default=None, help="show a progress bar on stderr (needs mechanism-mobility[progress])")
    bar.add_argument("--no-progress", dest="progress", action="store_false", help="never show a progress bar")
    p.add_argument("--good-transmission", type=float, default=GOOD_TRANSMISSION, metavar="LTI",
                   help="the good-transmission threshold of the local transmission index (default: %(default)g, as published)")
    p.add_argument("--no-transmission", action="store_true", help="leave out the transmission indices (columns iti, oti, lti, cti)")
    add_tolerance_option(p)
    p.set_defaults(run=run)


def _progress_wanted(choice: bool | None) -> bool:
    """An explicit choice, else a bar when stderr is a terminal and tqdm is installed."""
    return choice if choice is not None else sys.stderr.isatty() and importlib.util.find_spec("tqdm") is not None


def run(args: argparse.Namespace) -> int:
    tol = tolerance_from(args)
    if args.output == "-":  # the usual name of standard output
        args.output = None
    if args.json and args.format not in (None, "json"):
        raise RequestError("choose one output format", argument=f"--json and --format {args.format}")
    if args.output is not None and Path(args.output).suffix.lower() in PICTURE_FORMATS:
        raise RequestError(f"-o writes the table (text, csv or json); a picture is drawn by --plot {args.output}", argument=f"-o {args.output}")
    require_new_output(args.output, "-o", args.file)
    require_new_output(args.plot, "--plot", args.file, args.output)
    if args.plot is not None:  # before any work: a picture that cannot be drawn is refused now, not after the sweep
        from ..report.sweep_plot import require_drawable

        picture_path(args.plot, "--plot ")
        require_drawable(len(args.vary), f"--plot {args.plot}: ")
    if not 0.0 <= args.good_transmission <= 1.0:
        raise RequestError(f"--good-transmission must be a number in [0, 1], got {args.good_transmission:g}")
    if args.chunk_size < 1:
        raise RequestError(f"--chunk-size must be at least 1, got {args.chunk_size}")
    if args.workers is not None and args.scheduler is not None:
        raise RequestError("--workers sets the threads of this process; with --scheduler the cluster's workers run the chunks: give one of them")
    if args.workers is not None and not 1 <= args.workers <= MAX_WORKERS:
        raise RequestError(f"--workers must be between 1 and {MAX_WORKERS} (threads of this process; for more, use --scheduler), got {clipped(str(args.workers))}")
    mechanism = read_with_notes(args, outputs=((args.output, "-o"), (args.plot, "--plot"))).mechanism
    tol = tolerance_from(args, mechanism.precision)
    require_size(mechanism, "max_moving_joints", "a sweep", args.file)
    inputs = names_from(args.inputs, [j.name for j in mechanism.joints])
    if inputs is not None:
        try:
            actuated_inputs(mechanism, inputs)
        except MechanismError as exc:
            raise RequestError(exc.message, argument=f"--inputs {args.inputs}") from None
    result = sweep(mechanism, args.vary, actuated=inputs, tol=tol, max_poses=max_poses_from(args), chunk_size=args.chunk_size, scheduler=args.scheduler,
                   workers=args.workers, progress=_progress_wanted(args.progress), transmission=not args.no_transmission, good_threshold=args.good_transmission)
    fmt = "json" if args.json else args.format or _format_of(args.output)
    pieces = FORMATS[fmt](result)
    if args.output is not None:
        try:
            with atomic_output(args.output) as handle:  # the previous file intact until the new one is whole
                _write_pieces(handle, pieces)
        except OSError as exc:
            raise RequestError(f"cannot write it ({exc.strerror or exc})", argument=f"-o {args.output}") from None
        print(one_line(f"wrote {args.output}: {counted(result.size, 'pose', grouped=True)} of {result.name} ({fmt})"))
    else:
        _write_pieces(sys.stdout, pieces)
    if args.plot is not None:
        from ..report.sweep_plot import plot_sweep

        try:
            path = save_figure(plot_sweep(result), args.plot)
        except OSError as exc:
            raise RequestError(f"cannot write it ({exc.strerror or exc})", argument=f"--plot {args.plot}") from None
        note = f"wrote {path}: {'curve' if len(result.axes) == 1 else 'map' if len(result.axes) == 2 else 'slices'} of {result.name}"
        # a table printed on stdout stays a clean table: the note goes to stderr then
        print(one_line(note), file=sys.stderr if (args.output is None and fmt != "text") else sys.stdout)
    return 0


def _format_of(output: str | None) -> str:
    """The format an output's name asks for: ``csv`` or ``json`` by its suffix (in any case), else ``text``.

    Examples
    --------
    >>> _format_of("map.CSV"), _format_of("rows.json"), _format_of("notes.txt"), _format_of(None)
    ('csv', 'json', 'text', 'text')
    """
    suffix = "" if output is None else output.rpartition(".")[2].lower() if "." in output else ""
    return suffix if suffix in ("csv", "json") else "text"


def _write_pieces(handle: IO[str], pieces: Iterable[str]) -> None:
    """Write the pieces of an output as they come, ending it with a newline."""
    last = ""
    for piece in pieces:
        if piece:
            handle.write(piece)
            last = piece
    if not last.endswith("\n"):
        handle.write("\n")
