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

The core (loading, analysis, results) is imported with the package.  The
features built on it (regression checks, finite motion, actuation, flexures,
finite screws and synthesis, Jacobians, pictures) are imported on first use of
one of their names, so ``import mobility`` stays light:

>>> mobility.check_mechanism(m.replace(expected=mobility.Expected(dof=1, pattern="1R"))).status
'pass'
"""

from importlib import import_module
from typing import Any

from .analysis import analyze, gruebler_kutzbach
from .errors import AnalysisError, MechanismError, MechanismFileError, MobilityError
from .loader import load, loads
from .loop_closure import LoopClosure, loop_closure
from .model import Expected, Frame, Joint, Mechanism
from .result import LimbSystem, Margin, Result, ScrewAxis
from .tolerance import DEFAULT_TOLERANCE, Tolerance

__version__ = "0.1.0"

_LAZY = {
    # regression checks (mobility check)
    "check_mechanism": "check", "check_file": "check", "check_paths": "check",
    "CheckResult": "check", "CheckReport": "check", "Comparison": "check",
    # instantaneous vs full-cycle mobility
    "finite_mobility": "finite", "FiniteMobility": "finite", "sample_poses": "finite",
    # actuation spaces
    "check_actuation": "actuation", "enumerate_actuations": "actuation", "locked_dof": "actuation",
    "ActuationCheck": "actuation", "Enumeration": "actuation",
    # flexures
    "load_flexure": "flexure_loader", "loads_flexure": "flexure_loader",
    "flexure_spaces": "flexure", "check_force_lines": "flexure", "FlexureMechanism": "flexure",
    # finite screws, type synthesis, Jacobians
    "FiniteScrew": "finite_screws", "finite_screw": "finite_screws", "triangle_product": "finite_screws",
    "HalfTurnError": "finite_screws", "Limb": "finite_screws", "ScrewJoint": "finite_screws",
    "synthesize": "synthesis", "named_pattern": "synthesis", "MotionPattern": "synthesis", "assemble_pkm": "synthesis",
    "jacobian": "jacobian", "parallel_model": "jacobian",
    # pictures and Markdown
    "plot_mechanism": "plotting", "plot_graph": "plotting", "save_figure": "plotting",
    "markdown_report": "report_markdown",
}

__all__ = [
    "analyze",
    "gruebler_kutzbach",
    "load",
    "loads",
    "loop_closure",
    "LoopClosure",
    "Mechanism",
    "Joint",
    "Frame",
    "Expected",
    "Result",
    "ScrewAxis",
    "LimbSystem",
    "Margin",
    "Tolerance",
    "DEFAULT_TOLERANCE",
    "MobilityError",
    "MechanismError",
    "MechanismFileError",
    "AnalysisError",
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
