"""An interactive 3D view of a mechanism's freedoms and constraints, in a browser or a notebook.

``mobility view FILE -o FILE.html`` (and :meth:`View.write_html`) writes one
self-contained HTML page: the mechanism at its pose, its end effector's
freedoms and constraint wrenches, each layer switchable, hover text and a table
of the screws, DOF, pattern and mobility in the header (``docs/view.md``).  In
Jupyter a :class:`~mobility.core.result.Result` (and a :class:`View`) shows
itself as that view; several poses (or a sweep's) get a slider.  Needs plotly
(``pip install 'mechanism-mobility[view]'``); the scene (:mod:`~mobility.view.scene`)
is computed without it, :mod:`~mobility.view.labels` places the labels as the
browser will draw them, :mod:`~mobility.view.figure` and
:mod:`~mobility.view.page` make the figure and the page.
"""

from .scene import LAYERS, Glyph, Scene, build_scene
from .sweep import sweep_view
from .views import MAX_POSES, View, ViewFrame, mechanism_view, poses_view

__all__ = ["mechanism_view", "poses_view", "sweep_view", "View", "ViewFrame", "build_scene", "Scene", "Glyph", "LAYERS", "MAX_POSES"]
