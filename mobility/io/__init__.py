"""Reading and writing mechanism files: YAML, MJCF or URDF text in, a :class:`~mobility.core.model.Mechanism` out.

:mod:`~mobility.io.limits` bounds every document; :mod:`~mobility.io.yaml_source`
and :mod:`~mobility.io.xml_source` parse within those bounds, keeping every
key's line; :mod:`~mobility.io.reader` and :mod:`~mobility.io.loader` read
the format (``docs/spec-v1.md``); the robot readers (:mod:`~mobility.io.robot_files`)
build a joint graph from MJCF or URDF; :mod:`~mobility.io.writer` writes YAML
back.  Loaders know the model and nothing of screws.
"""

from .loader import load, loads

__all__ = ["load", "loads"]
