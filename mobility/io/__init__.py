"""Reading and writing mechanism files: YAML, MJCF or URDF text in, a :class:`~mobility.core.model.Mechanism` out.

Modules, in data-flow order:

``limits``
    every bound a document may not exceed (size, depth, counts), in one place.
``yaml_source``, ``xml_source``
    YAML and XML parsed within those bounds, with the line of every key or
    element kept for one-line error messages.
``expressions``
    the safe arithmetic of ``parameters`` and numeric fields.
``reader``
    :class:`~mobility.io.reader.DocumentReader`: the values of a parsed
    document (sections, numbers, vectors, names, units, frames), every error
    naming file, line and key; the mechanism loader and the flexure loader
    build on it.
``loader``
    the format of ``docs/spec-v1.md`` and its extensions: :func:`load`, :func:`loads`.
``robot_tree``, ``mjcf_scan``, ``mjcf``, ``urdf``, ``closures``, ``robot_files``
    robot descriptions: a tree of bodies and the joint graph it makes; an
    MJCF file and its includes checked before MuJoCo reads them; MJCF read
    as MuJoCo compiles it; URDF; loop closures by option or side file;
    recognising a robot file and reading it (:func:`~mobility.io.robot_files.read_robot`).
``writer``
    a mechanism written back as YAML text (``mobility convert``).

Loaders know the model and nothing of screws.
"""

from .loader import load, loads

__all__ = ["load", "loads"]
