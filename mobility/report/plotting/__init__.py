"""Pictures: a mechanism at its pose with its freedoms and constraints, and its joint graph.

matplotlib is optional (``pip install 'mechanism-mobility[plot]'``), imported only when a picture is
drawn: ``sketch``, ``views``, ``scene``, ``geometry`` and ``style`` (where each thing is drawn) need none.
Every drawn answer carries a ``gid`` (``"mobility:translation:0"``, ``"mobility:link:<name>"``,
``"mobility:tree:series"``...), so programs and tests can read the picture back.

Examples
--------
>>> from mobility import Joint, Mechanism, analyze
>>> m = Mechanism("slider", "g", "s", (Joint("P1", "P", ("g", "s"), axis=(0, 0, 1)),))
>>> r = analyze(m)
>>> [len(x) for x in (build_scene(r, sketch(m), constraints=True).translations, r.couples)]
[1, 3]
"""

from .backend import FORMATS, picture_path, save_figure
from .graph import plot_graph
from .mechanism import plot_mechanism
from .scene import Scene, build_scene
from .sketch import Sketch, sketch
from .style import COLORS, JOINT_STYLE, LIMB_COLORS
from .views import choose_views

__all__ = ["plot_mechanism", "plot_graph", "save_figure", "picture_path", "FORMATS", "Sketch", "sketch", "choose_views", "Scene", "build_scene",
           "COLORS", "JOINT_STYLE", "LIMB_COLORS"]
