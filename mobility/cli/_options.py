"""Options shared by several subcommands: each ``add_*`` function registers them, its partner reads them back checked.

Every subcommand reading one mechanism file registers it with
:func:`add_mechanism_file` (``FILE`` and the robot description options) and
reads it with :func:`read_with_notes`, so that every command reads YAML, MJCF
and URDF alike.
"""

from __future__ import annotations

import argparse
import os
import stat
import sys
from typing import Any, Collection

from ..core.model import Mechanism
from ..core.validation import integer_from_text, number_from_text
from ..core.tolerance import DEFAULT_TOLERANCE, Tolerance, file_tolerance
from ..errors import RequestError, one_line
from ..io.files import os_reason, require_not_pipe
from ..io.loader import FileRead, read_file

__all__ = ["add_tolerance_option", "tolerance_from", "add_pose_sampler_options", "sampled_poses", "MECHANISM_FILE_HELP", "add_mechanism_file",
           "robot_options_from", "read_mechanism", "read_with_notes", "names_from", "MAX_SAMPLES", "require_sampler_options", "require_new_output",
           "add_max_poses_option", "max_poses_from", "require_option_for", "number_option", "integer_option"]


def number_option(text: str) -> float:
    """The ``type`` of an option that takes a number: ``float``, but digits in ASCII only, no ``_`` (``--tol \u0661e-9`` and ``--tol 1_0e-9`` are refused, as in a file; :func:`~mobility.core.validation.number_from_text`)."""
    return number_from_text(text)


def integer_option(text: str) -> int:
    """The ``type`` of an option that takes an integer: ``int``, but digits in ASCII only, no ``_`` (:func:`~mobility.core.validation.integer_from_text`)."""
    return integer_from_text(text)


number_option.__name__ = "float"  # argparse names the type in its message: "invalid float value: 'x'"
integer_option.__name__ = "int"


def add_tolerance_option(parser: argparse.ArgumentParser) -> None:
    """Add ``--tol``, the relative rank threshold of the tolerance policy."""
    parser.add_argument("--tol", type=number_option, default=None,
                        help=f"relative rank threshold, in [{DEFAULT_TOLERANCE.inexact:g}, {DEFAULT_TOLERANCE.near_singular:g}) (default: {DEFAULT_TOLERANCE.rank:g}, "
                             "or more for a file whose numbers are rounded: never finer than the file)")


def tolerance_from(args: argparse.Namespace, precision: float | None = None) -> Tolerance:
    """The :class:`~mobility.core.tolerance.Tolerance` of ``--tol``, else :func:`~mobility.core.tolerance.file_tolerance` of the file's ``precision``."""
    if args.tol is None:
        return file_tolerance(precision)
    try:
        return Tolerance(rank=args.tol)
    except RequestError:
        raise RequestError(f"--tol must lie in [{DEFAULT_TOLERANCE.inexact:g}, {DEFAULT_TOLERANCE.near_singular:g}), got {args.tol:g}") from None


def add_pose_sampler_options(parser: argparse.ArgumentParser, *, samples_help: str, samples_group: argparse._ActionsContainer | None = None,
                             most: int | None = None) -> None:
    """Add ``--samples N``, ``--step`` and ``--seed``: further poses reached by moving the mechanism.

    ``samples_help`` says what the subcommand does with the poses; ``--samples``
    joins ``samples_group`` if given; ``most`` is the largest ``--samples`` the
    help names when the command checks a bound below :data:`MAX_SAMPLES` itself.
    """
    from ..core.poses import DEFAULT_STEP, MAX_STEP  # the finite kinematics: imported only by the commands that move

    (samples_group or parser).add_argument("--samples", type=integer_option, default=0, metavar="N", help=samples_help + f", 0 to {MAX_SAMPLES if most is None else most} (default: %(default)s)")
    parser.add_argument("--step", type=number_option, default=DEFAULT_STEP,
                        help=f"step of the pose sampler, in (0, {MAX_STEP:g}]: a joint-space distance (radians, lengths over the mechanism's size) (default: %(default)g)")
    parser.add_argument("--seed", type=integer_option, default=0, help="seed of the pose sampler (default: %(default)d)")


def add_max_poses_option(parser: argparse.ArgumentParser, *, what: str = "refuse a larger grid") -> None:
    """Add ``--max-poses N``, the largest grid of a ``--vary`` sweep (default :data:`mobility.sweeps.DEFAULT_MAX_POSES`, as ``mobility sweep``)."""
    from ..sweeps import DEFAULT_MAX_POSES  # the sweeps: imported only by the commands that vary joints

    parser.add_argument("--max-poses", type=integer_option, default=DEFAULT_MAX_POSES, metavar="N", help=what + " (default: %(default)d)")


def max_poses_from(args: argparse.Namespace) -> int:
    """``--max-poses``, checked: at least 1, else a :class:`RequestError` (a larger grid is refused by :func:`mobility.sweeps.sweep` itself)."""
    if args.max_poses < 1:
        raise RequestError(f"--max-poses must be at least 1, got {args.max_poses}")
    return args.max_poses


MAX_SAMPLES = 1000
"""The most poses ``--samples`` may ask for (each is a loop closure and an analysis)."""


def require_sampler_options(args: argparse.Namespace) -> None:
    """``--samples`` in ``[0, MAX_SAMPLES]``, ``--seed`` not negative, ``--step`` in ``(0, 1]`` (a joint-space distance), else a :class:`RequestError`."""
    from ..core.poses import MAX_STEP

    if not (0 <= args.samples <= MAX_SAMPLES) or not (0.0 < args.step <= MAX_STEP) or args.seed < 0:
        raise RequestError(f"--samples must lie in [0, {MAX_SAMPLES}], --seed must not be negative and --step must lie in (0, {MAX_STEP:g}]; "
                           f"got {args.samples}, {args.seed} and {args.step!r}")


def sampled_poses(args: argparse.Namespace, mechanism: Mechanism) -> list[Mechanism]:
    """The poses asked for by ``--samples``, ``--step`` and ``--seed`` (none for ``--samples 0``), checked by :func:`require_sampler_options`."""
    require_sampler_options(args)
    if not args.samples:
        return []
    from ..core.poses import sample_poses  # the finite kinematics: imported only by the commands that move

    return sample_poses(mechanism, args.samples, step=args.step, seed=args.seed)


MECHANISM_FILE_HELP = "mechanism file (YAML) or robot description (MJCF, URDF)"
"""The help of the ``FILE`` argument of every subcommand that reads one mechanism file."""


class StoreOnce(argparse.Action):
    """Store an option's value, refusing it given twice (the last would win silently, the first never read)."""

    def __call__(self, parser: argparse.ArgumentParser, namespace: argparse.Namespace, values: Any, option_string: str | None = None) -> None:
        if getattr(namespace, self.dest, None) is not None:
            parser.error(f"{option_string} given twice; expected it once")
        setattr(namespace, self.dest, values)


def add_mechanism_file(parser: argparse.ArgumentParser, *, file_help: str = MECHANISM_FILE_HELP) -> None:
    """Add the ``file`` argument (YAML, MJCF or URDF, helped by ``file_help``) and the options of robot description files."""
    parser.add_argument("file", help=file_help)
    g = parser.add_argument_group("robot description files (MJCF, URDF)")
    g.add_argument("--ground", metavar="BODY", action=StoreOnce, help="the fixed body (default: the world or root body)")
    g.add_argument("--end-effector", metavar="BODY", action=StoreOnce, help="the body whose freedom is reported (default: the body farthest from the ground)")
    g.add_argument("--floating", action="store_true", help="keep the 6 freedoms of free/floating joints (default: treat them as fixed)")
    g.add_argument("--ignore-unsupported", action="store_true", help="leave out what the model cannot express (flex bodies, spatial-tendon or one-joint equalities, some actuators) with a note instead of failing")
    g.add_argument("--close", nargs=2, action="append", metavar=("A", "B"), default=[],
                   help="close a loop: bodies A and B, whose origins coincide, are joined by a spherical joint (repeatable)")
    g.add_argument("--closures", metavar="FILE", action=StoreOnce, help="YAML file of closing joints in the project's format (links are body names)")


OPTION_SPELLING = {"ground": "--ground", "end_effector": "--end-effector", "floating": "--floating",
                   "ignore_unsupported": "--ignore-unsupported", "close": "--close", "closures": "--closures"}
"""The command-line option of each keyword of :func:`mobility.load` that :func:`robot_options_from` gives."""


def robot_options_from(args: argparse.Namespace) -> dict[str, Any]:
    """The robot options given on the command line, as keywords of :func:`mobility.load` (those left at their default are omitted).

    An empty ``--ground``, ``--end-effector`` or ``--closures`` (which would read as the option left out) is a :class:`RequestError`.
    """
    for option, value, what in (("--ground", args.ground, "a body name"), ("--end-effector", args.end_effector, "a body name"),
                                ("--closures", args.closures, "a file name")):
        if value == "":
            raise RequestError(argument=option, expected=what, got="an empty one")
    values = {key: getattr(args, key) for key in OPTION_SPELLING} | {"close": tuple(tuple(p) for p in args.close)}
    return {k: v for k, v in values.items() if v not in (None, False, ())}


def read_mechanism(args: argparse.Namespace, path: str | None = None) -> FileRead:
    """The mechanism of ``path`` (default: ``args.file``), read with the robot options of ``args``, the notes of the reading and the files read.

    Robot options given for a mechanism file (YAML) are a :class:`RequestError`, named as typed.
    """
    return read_file(args.file if path is None else path, spelling=OPTION_SPELLING, **robot_options_from(args))


def read_with_notes(args: argparse.Namespace, *, outputs: tuple[tuple[str | None, str], ...] = ()) -> FileRead:
    """:func:`read_mechanism` of ``args.file``, its notes on stderr; an ``(output, option)`` of ``outputs`` that would overwrite a file read is refused."""
    read = read_mechanism(args)
    for output, option in outputs:
        require_new_output(output, option, *read.files)
    for note in read.notes:
        print(f"mobility: note: {one_line(note)}", file=sys.stderr)
    return read


def names_from(text: str | None, known: Collection[str] = (), option: str = "--inputs") -> list[str] | None:
    """The names of a comma-separated option (``--inputs P1, P2``), ``None`` when the option was not given.

    A name may hold commas (``"hip,left"``): parts that, joined again, make one
    of the ``known`` names (or ``NAME.k``) are that name, the longest run first.

    Examples
    --------
    >>> names_from("P1, P2,,P3"), names_from(None)
    (['P1', 'P2', 'P3'], None)
    >>> names_from("hip,left, knee,hip,left.1", known=("hip,left", "knee"))
    ['hip,left', 'knee', 'hip,left.1']
    """
    if text is None:
        return None
    if not text.replace(",", "").strip():
        raise RequestError(argument=f"{option} {text!r}", expected="one or more joint names, separated by commas")
    names_set = set(known)
    is_name = lambda candidate: candidate in names_set or candidate.rpartition(".")[0] in names_set  # noqa: E731
    spans: dict[str, set[int]] = {}  # the first part of each name that holds commas -> how many parts it has
    for name in names_set:
        if "," in name:
            spans.setdefault(name.split(",", 1)[0].strip(), set()).add(name.count(",") + 1)
    parts = text.split(",")
    names, at = [], 0
    while at < len(parts):  # only the spans of the names that start with this part are tried: linear in the text
        tried = sorted((k for k in spans.get(parts[at].strip(), ()) if at + k <= len(parts)), reverse=True)
        run = next((span for span in tried if is_name(",".join(parts[at : at + span]).strip())), 1)
        names.append(",".join(parts[at : at + run]).strip())
        at += run
    return [n for n in names if n]


def require_new_output(output: str | None, option: str, *inputs: str | None) -> None:
    """Refuse an output that would destroy an input or never be written: one of ``inputs`` (by any path), a directory, a pipe, a socket, or a path that cannot be looked up (a symbolic link loop).

    Examples
    --------
    >>> require_new_output("mechanisms/four_bar.yaml", "-o", "mechanisms/../mechanisms/four_bar.yaml")
    Traceback (most recent call last):
    mobility.errors.RequestError: -o mechanisms/four_bar.yaml: the same file as mechanisms/../mechanisms/four_bar.yaml, which would be overwritten
    """
    if output is None:
        return
    where = f"{option} {output}"
    if output.endswith(("/", os.sep)):  # `-o newdir/` would write a file called newdir
        raise RequestError(argument=where, expected=f"a file name, not a folder (it ends with {output[-1]})")
    if stat.S_ISDIR(require_not_pipe(output, f"a file to write for {option} (writing to a pipe would wait for a reader)")):
        raise RequestError("is a directory, expected a file to write", argument=where)
    try:
        os.stat(output)
    except FileNotFoundError:  # a new file: its folder must be there
        folder = os.path.dirname(os.path.abspath(output))
        if not os.path.isdir(folder):
            raise RequestError(f"cannot write there: the folder {folder} does not exist", argument=where) from None
    except OSError as exc:  # before any work: writing there would fail after it
        raise RequestError(f"cannot write there: {os_reason(exc)}", argument=where) from None
    for given in inputs:
        if given is None:
            continue
        try:  # realpath, unlike Path.resolve, stops at a symbolic link loop instead of raising
            same = os.path.realpath(output) == os.path.realpath(given) or (os.path.exists(output) and os.path.samefile(output, given))
        except (OSError, ValueError):
            same = False
        if same:
            raise RequestError(f"the same file as {given}, which would be overwritten", argument=where)


def require_option_for(args: argparse.Namespace, dest: str, option: str, needs: str, present: bool, what: str) -> None:
    """Refuse ``option`` typed without ``needs`` (``present`` tells whether that is given): it would be left unread.

    Given means typed on the command line (``args.given_options``), whatever its value.

    Examples
    --------
    >>> args = argparse.Namespace(given_options=frozenset({"max_poses"}))
    >>> require_option_for(args, "max_poses", "--max-poses", "--vary", False, "it bounds the grid of a sweep")
    Traceback (most recent call last):
    mobility.errors.RequestError: --max-poses needs --vary (it bounds the grid of a sweep); give --vary too, or leave --max-poses out
    """
    if not present and dest in getattr(args, "given_options", ()):
        raise RequestError(f"{option} needs {needs} ({what}); give {needs} too, or leave {option} out")
