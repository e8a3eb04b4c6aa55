"""Read mechanism files into :class:`~mobility.core.model.Mechanism` objects.

YAML (``docs/file-format.md``, read by :mod:`mobility.io.mechanism_reader` within :mod:`mobility.io.limits`), or a robot
description (:mod:`mobility.io.robot_files`).

Examples
--------
>>> text = '''
... name: slider
... ground: g
... end_effector: s
... joints:
...   - {name: P1, type: P, links: [g, s], axis: [0, 0, 2]}
... '''
>>> m = loads(text)
>>> m.joints[0].axis
(0.0, 0.0, 1.0)
>>> loads(text.replace("[0, 0, 2]", "[0, 2]"), file="slider.yaml")
Traceback (most recent call last):
...
mobility.errors.MechanismFileError: slider.yaml:6: joints[0].axis: expected a list of 3 numbers, got 2
"""

from __future__ import annotations

from pathlib import Path
from typing import Any, Mapping, NamedTuple

from ..core.model import Mechanism
from ..errors import RequestError
from .files import file_name
from .limits import Limits, current_limits
from .mechanism_reader import JOINT_KEYS, TOP_LEVEL_KEYS, is_flexure_document, read_mechanism
from .yaml_source import parse_yaml, read_text

__all__ = ["load", "loads", "read_file", "FileRead", "is_robot_description", "read_mechanism", "is_flexure_document", "TOP_LEVEL_KEYS", "JOINT_KEYS"]


def load(path: str | Path, *, limits: Limits | None = None, **robot_options: Any) -> Mechanism:
    """Load a mechanism file.

    Parameters
    ----------
    path : str or Path
        A YAML mechanism file, or a robot description (MJCF, URDF) recognised
        by extension or content (:mod:`mobility.io.robot_files`).
    limits : Limits, optional
        Bounds on the document (default: :func:`~mobility.io.limits.current_limits`).
    **robot_options
        For robot descriptions: the fields of :class:`~mobility.io.robot_tree.RobotOptions`.

    Raises
    ------
    MechanismFileError
        When the file cannot be read or breaks the format (file, line, key, what was expected).
    RequestError
        When ``path`` is not a file name, ``limits`` not a ``Limits``, or a
        robot option is unknown, of the wrong type, or given for a YAML file.

    Examples
    --------
    >>> m = load("mechanisms/four_bar.yaml")
    >>> m.ground, m.end_effector, [j.name for j in m.joints]
    ('ground', 'coupler', ['A', 'B', 'C', 'D'])
    """
    return read_file(path, limits=limits, **robot_options).mechanism


class FileRead(NamedTuple):
    """A mechanism read from a file, the notes of its reading, every file read for it (the file first) and the joints that close loops."""

    mechanism: Mechanism
    notes: tuple[str, ...] = ()
    files: tuple[str, ...] = ()
    closures: tuple[str, ...] = ()


def is_robot_description(path: str | Path) -> bool:
    """Whether ``path`` is read as a robot description (MJCF, URDF), the one place this is decided (by extension or content).

    Examples
    --------
    >>> is_robot_description("mechanisms/four_bar.yaml"), is_robot_description("arm.urdf")
    (False, True)
    """
    if Path(path).suffix.lower() in (".yaml", ".yml"):
        return False
    from .robot_files import is_robot_file  # robot descriptions are read only when given

    return is_robot_file(path)


def read_file(path: str | Path, *, limits: Limits | None = None, spelling: Mapping[str, str] | None = None, **robot_options: Any) -> FileRead:
    """:func:`load`, with the notes of the reading and the files read (the command line's reader).

    ``spelling`` names the robot options as the user wrote them (``{"ground": "--ground"}``), for a refusal.

    Examples
    --------
    >>> read = read_file("mechanisms/four_bar.yaml")
    >>> read.mechanism.name, read.files
    ('planar four-bar', ('mechanisms/four_bar.yaml',))
    """
    file_name(path, "load")
    limits = _limits_argument(limits)
    if not is_robot_description(path):
        if robot_options:
            from .robot_files import require_no_robot_options

            require_no_robot_options(path, robot_options, spelling)
        return FileRead(_read_yaml(read_text(path, limits), str(path), limits), files=(str(path),))
    from .robot_files import read_robot

    robot = read_robot(path, **robot_options)  # its files: the robot file, the files it includes, the closures file
    return FileRead(robot.mechanism, tuple(robot.notes), tuple(robot.files), robot.closures)


def loads(text: str, file: str = "<string>", *, limits: Limits | None = None) -> Mechanism:
    """Load a mechanism from YAML text (see :func:`load`).

    Examples
    --------
    >>> loads("{name: slider, ground: g, end_effector: s, joints: [{name: p, type: P, links: [g, s], axis: [1, 0, 0]}]}").name
    'slider'
    >>> loads(3)
    Traceback (most recent call last):
    mobility.errors.RequestError: loads: expected the text of a mechanism file (str), got int
    """
    if not isinstance(text, str):
        raise RequestError(caller="loads", expected="the text of a mechanism file (str)", got=type(text).__name__)
    return _read_yaml(text, file_name(file, "loads: file"), _limits_argument(limits))


def _read_yaml(text: str, file: str, limits: Limits) -> Mechanism:
    """The mechanism of YAML ``text``, its arguments checked by :func:`load` or :func:`loads`."""
    data, positions = parse_yaml(text, file, limits)
    return read_mechanism(data, positions, file, limits=limits)


def _limits_argument(limits: object) -> Limits:
    """``limits`` if it is a :class:`Limits`, the current limits for ``None``; a :class:`RequestError` otherwise."""
    if limits is not None and not isinstance(limits, Limits):
        raise RequestError(argument="limits", expected="a Limits (mobility.io.limits.Limits) or None", got=type(limits).__name__)
    return current_limits(limits)
