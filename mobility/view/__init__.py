"""An interactive 3D view of a mechanism's freedoms and constraints, in a browser or a notebook.

``mobility view FILE -o FILE.html`` (and :meth:`View.write_html`) writes one
self-contained HTML page: the mechanism at its pose (links, joints by type,
the end effector), its end effector's freedoms (translation arrows, rotation
axes with their pitch) and constraint wrenches (force lines, couples), each
layer switchable, labels placed clear of each other and of the axes' ticks,
hover text with each screw's numbers and a table of them beside the plot,
DOF, pattern and mobility in the header; rotate, zoom and pan with the mouse.  In Jupyter a
:class:`~mobility.core.result.Result` (and a :class:`View`) shows itself as
that view.  Several poses (or a sweep's) get a slider.

Needs plotly (``pip install 'mechanism-mobility[view]'``); the scene itself
(:mod:`~mobility.view.scene`) is computed without it.

Modules
-------
``geometry``
    arrowheads, arcs, helices, plates as arrays.
``describe``
    hover text and titles.
``scene``
    the glyphs of one pose, in layers.
``labels``
    the first view's zoom and where each label sits, as the browser will
    draw them (plotly's orthographic projection, computed here).
``figure``
    the plotly figure (a dict) of one or several poses.
``page``
    the self-contained HTML page.
``views``
    :class:`View`, :func:`mechanism_view`, :func:`poses_view`.
``sweep``
    :func:`sweep_view`: a sweep result's poses on a slider.
``notebook``
    the Jupyter display of a :class:`~mobility.core.result.Result` and of a
    sweep result.
"""

from .scene import LAYERS, Glyph, Scene, build_scene
from .sweep import sweep_view
from .views import MAX_POSES, View, ViewFrame, mechanism_view, poses_view

__all__ = ["mechanism_view", "poses_view", "sweep_view", "View", "ViewFrame", "build_scene", "Scene", "Glyph", "LAYERS", "MAX_POSES"]
