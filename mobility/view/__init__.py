"""An interactive 3D view of a mechanism's freedoms and constraints, in a browser or a notebook.

``mobility view FILE -o FILE.html`` and :meth:`View.write_html` write one self-contained HTML page; in Jupyter
a :class:`~mobility.core.result.Result` (and a :class:`View`) shows itself as that view (docs/view.md).  Needs
plotly (``pip install 'mechanism-mobility[view]'``), but for :mod:`~mobility.view.scene` and :mod:`~mobility.view.labels`.
"""

from .scene import LAYERS, Glyph, Scene, build_scene
from .sweep import sweep_view
from .views import MAX_POSES, View, ViewFrame, mechanism_view, poses_view

__all__ = ["mechanism_view", "poses_view", "sweep_view", "View", "ViewFrame", "build_scene", "Scene", "Glyph", "LAYERS", "MAX_POSES"]
