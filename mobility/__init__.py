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
"""

from .analysis import analyze, gruebler_kutzbach
from .errors import AnalysisError, MechanismError, MechanismFileError, MobilityError
from .loader import load, loads
from .model import Expected, Frame, Joint, Mechanism
from .result import LimbSystem, Margin, Result, ScrewAxis
from .tolerance import DEFAULT_TOLERANCE, Tolerance

__version__ = "0.1.0"

__all__ = [
    "analyze",
    "gruebler_kutzbach",
    "load",
    "loads",
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
]
