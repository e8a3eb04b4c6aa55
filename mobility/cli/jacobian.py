"""``mobility jacobian FILE``: the Jacobian of a parallel mechanism whose limbs are serial chains, by differentiating finite screws."""

from __future__ import annotations

import argparse

from ..errors import MechanismError, MechanismFileError
from ..jacobians import jacobian
from ..report.jacobian import jacobian_json, jacobian_text
from ._options import MECHANISM_FILE_HELP, add_mechanism_file, add_tolerance_option, names_from, read_with_notes, tolerance_from

ORDER = 45
EXIT_STATUS = "0 the Jacobian has rank 6 (the platform is controlled, redundantly or not), 1 it is singular, 2 bad input (one line on standard error)"


def register(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser("jacobian",
                       help="Jacobian of a parallel mechanism (actuation and constraint wrenches) from its finite screws",
                       description="Jacobian by differentiating the limbs' finite screws (Sun et al. 2018, Eq. 26): "
                       "J $ = [actuated rates; 0] for the platform twist $ = [w; v].")
    add_mechanism_file(p, file_help=MECHANISM_FILE_HELP + " whose limbs are serial chains")
    p.add_argument("--actuated", default=None, metavar="A,B,...", help="actuated joints (default: those marked actuated: true); NAME.k picks freedom k (from 0, as reports label it) of a multi-DOF joint")
    p.add_argument("--json", action="store_true", help="print one JSON object")
    add_tolerance_option(p)
    p.set_defaults(run=run)


def run(args: argparse.Namespace) -> int:
    tol = tolerance_from(args)
    mechanism = read_with_notes(args).mechanism
    tol = tolerance_from(args, mechanism.precision)
    names = names_from(args.actuated, [j.name for j in mechanism.joints], "--actuated")
    try:
        result = jacobian(mechanism, actuated=names, tol=tol)
    except MechanismFileError:
        raise
    except MechanismError as exc:
        raise MechanismFileError(exc.key, exc.message, file=args.file) from None
    print(jacobian_json(result) if args.json else jacobian_text(result, mechanism.length_unit))
    return 1 if result.singular else 0
