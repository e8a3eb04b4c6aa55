"""Pictures: a mechanism at its pose with its freedoms and constraints, and its joint graph.

:func:`plot_mechanism` draws the mechanism in 3D with the answer of
:func:`mobility.analyze` on its end effector; :func:`plot_graph` draws the
joint graph beside the series/parallel tree the analysis reduced it to;
:func:`save_figure` writes either (or a sweep's picture) as PNG, SVG or PDF.  matplotlib is optional
(``pip install 'mechanism-mobility[plot]'``), imported only when a picture is drawn.

Modules, each with one job (those marked * need no matplotlib):

``sketch`` *
    where each joint is drawn, and the size of the scene.
``views`` *
    viewpoints where nothing important overlaps.
``scene`` *
    where the freedoms and constraint wrenches are drawn.
``geometry`` * and ``style`` *
    small vector helpers; joint symbols and colours.
``glyphs``
    the 3D drawing primitives (arrows, rotation marks, links, joints).
``mechanism``, ``graph``
    the two pictures.
``backend``
    matplotlib on demand, figures without pyplot, saving.

Every drawn answer carries a ``gid`` (``"mobility:translation:0"``,
``"mobility:rotation-axis:1"``, ``"mobility:force:0"``, ``"mobility:couple:0"``,
``"mobility:link:<name>"``, ``"mobility:joints:<type>"``, ``"mobility:tree:series"``...),
so programs and tests can read the picture back.

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

__all__ = [
    "plot_mechanism",
    "plot_graph",
    "save_figure",
    "picture_path",
    "FORMATS",
    "Sketch",
    "sketch",
    "choose_views",
    "Scene",
    "build_scene",
    "COLORS",
    "JOINT_STYLE",
    "LIMB_COLORS",
]
