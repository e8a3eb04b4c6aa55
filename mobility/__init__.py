"""mobility: how can a mechanism move?  Screw-theory mobility analysis of joint graphs.

Load a mechanism file (or build a :class:`Mechanism` in code) and analyse it:

>>> import mobility
>>> m = mobility.loads('''
... name: planar four-bar
... ground: ground
... end_effector: coupler
... joints:
...   - {name: A, type: R, links: [ground, crank],   axis: [0, 0, 1], point: [0, 0, 0]}
...   - {name: B, type: R, links: [crank, coupler],  axis: [0, 0, 1], point: [1, 2, 0]}
...   - {name: C, type: R, links: [coupler, rocker], axis: [0, 0, 1], point: [4, 2.5, 0]}
...   - {name: D, type: R, links: [rocker, ground],  axis: [0, 0, 1], point: [5, 0, 0]}
... ''')
>>> r = mobility.analyze(m)
>>> r.dof, r.pattern, r.mobility, r.gruebler_kutzbach
(1, '1R', 1, -2)

The features built on the core (checks, finite motion, actuation, flexures,
synthesis, Jacobians, pictures, views) are imported on first use of one of
their names, so ``import mobility`` stays light:

>>> mobility.check_mechanism(m.replace(expected=mobility.Expected(dof=1, pattern="1R"))).status
'pass'

The library of classic mechanisms ships inside the package
(:mod:`mobility.library`), so its files are there without a clone:

>>> mobility.analyze(mobility.load(mobility.library.path("3prs"))).pattern
'1T2R'

Inside IPython (a notebook) a :class:`Result` displays itself as its
interactive 3D view (:mod:`mobility.view`).
"""

import sys
from importlib import import_module
from typing import Any

from .core.analysis import analyze, gruebler_kutzbach
from .errors import (
    AnalysisError,
    HalfTurnError,
    MechanismCheckFailed,
    MechanismError,
    MechanismFileError,
    MissingExtraError,
    MobilityError,
    PlotFormatError,
    PlottingUnavailableError,
    RequestError,
    SynthesisError,
)
from .io.loader import load, loads
from .core.loop_closure import LoopClosure, loop_closure
from .core.expected import Expected
from .core.model import Coupling, Frame, Joint, Mechanism
from .core.result import LimbSystem, Margin, Result, ScrewAxis
from .core.tolerance import DEFAULT_TOLERANCE, Tolerance
from . import library

__version__ = "0.2.0"
"""The version of the package: the one place it is written (``pyproject.toml`` reads it, ``mobility --version`` prints it)."""

_LAZY = {
    # regression checks (mobility check)
    "check_mechanism": "testing", "check_file": "testing", "check_paths": "testing",
    "CheckResult": "testing", "CheckReport": "testing", "Comparison": "testing",
    # instantaneous vs full-cycle mobility
    "finite_mobility": "finite", "FiniteMobility": "finite", "sample_poses": "core.poses",
    # actuation spaces
    "check_actuation": "actuation", "enumerate_actuations": "actuation", "locked_dof": "actuation",
    "ActuationCheck": "actuation", "Enumeration": "actuation",
    # flexures
    "load_flexure": "flexure", "loads_flexure": "flexure",
    "flexure_spaces": "flexure", "check_force_lines": "flexure", "FlexureMechanism": "flexure",
    # finite screws, type synthesis, Jacobians
    "FiniteScrew": "core.finite_screws", "finite_screw": "core.finite_screws", "triangle_product": "core.finite_screws",
    "Limb": "core.finite_screws", "ScrewJoint": "core.finite_screws",
    "synthesize": "synthesis", "named_pattern": "synthesis", "MotionPattern": "synthesis", "assemble_pkm": "synthesis",
    "jacobian": "jacobians", "parallel_model": "jacobians",
    # pictures and Markdown
    "plot_mechanism": "report.plotting", "plot_graph": "report.plotting", "save_figure": "report.plotting",
    "markdown_report": "report.markdown",
    # sweeps: mobility, singularity and actuation maps over a grid of poses
    "sweep": "sweeps", "SweepResult": "sweeps",
    # motion/force transmission indices (ITI, OTI, LTI, CTI) at one pose
    "check_transmission": "sweeps.batch_transmission", "TransmissionCheck": "transmission",
    # robot description files (MJCF, URDF): the mechanism with the notes of its reading
    "read_robot": "io.robot_files",
    # the interactive 3D view
    "mechanism_view": "view", "poses_view": "view", "sweep_view": "view", "View": "view", "ViewFrame": "view",
}

__all__ = [
    "analyze", "gruebler_kutzbach", "load", "loads", "loop_closure", "LoopClosure", "Mechanism", "Joint", "Coupling", "Frame",
    "Expected", "Result", "ScrewAxis", "LimbSystem", "Margin", "Tolerance", "DEFAULT_TOLERANCE",
    "library",  # the bundled library of classic mechanisms and flexure examples (mobility.library.path("3prs"))
    # every error class of mobility.errors: what the package raises on purpose
    "MobilityError", "MechanismError", "MechanismFileError", "MechanismCheckFailed", "RequestError", "SynthesisError",
    "PlotFormatError", "AnalysisError", "HalfTurnError", "MissingExtraError", "PlottingUnavailableError",
    *_LAZY,
]


def __getattr__(name: str) -> Any:
    module = _LAZY.get(name)
    if module is None:
        raise AttributeError(f"module 'mobility' has no attribute {name!r}")
    value = getattr(import_module(f".{module}", __name__), name)
    globals()[name] = value
    return value


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(_LAZY))


def _display_results_in_ipython() -> None:
    """Inside IPython, show a :class:`Result` as its interactive 3D view (:func:`mobility.view.notebook.register_display`; the core knows nothing of views)."""
    ipython = sys.modules.get("IPython")
    shell = ipython.get_ipython() if ipython is not None and hasattr(ipython, "get_ipython") else None
    if shell is not None and hasattr(shell, "display_formatter"):
        from .view.notebook import register_display

        register_display(shell)


_display_results_in_ipython()
