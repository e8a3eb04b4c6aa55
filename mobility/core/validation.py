"""The value checkers of the package: one idiom, ``require_*``, that returns the value checked or raises.

A public function checks each argument once, at its boundary, with these;
the code below trusts what they return.  A refusal is an error with fields
(:class:`~mobility.errors.MechanismError`: key and problem;
:class:`~mobility.errors.RequestError`: caller, argument, expected, got) that
writes its own message.  :func:`require_integer` and :func:`require_real` are
the one test of "an integer" and "a real number"; a caller with a message of
its own catches their error and raises its own ``from None``.
"""

from __future__ import annotations

import math
import numbers
import operator
from typing import Any, Iterable, Mapping, TypeVar

import numpy as np

from ..errors import MechanismError, RequestError, name_problem, shown_argument
from .tolerance import UNIT_ROUND_OFF, binary_scale

__all__ = ["Vector", "require_vector", "require_instance", "require_name", "require_graph_names", "require_unique_names",
           "require_no_repeats", "require_ground_and_end_effector", "joint_names",
           "require_integer", "require_real", "require_bool", "number_from_text", "integer_from_text"]

_T = TypeVar("_T")

Vector = tuple[float, float, float]


def require_vector(value: Any, key: str, *, direction: bool = False) -> Vector:
    """A 3-vector of finite numbers, normalised if it is a direction (any finite size: scaled before squaring); else a :class:`MechanismError`.

    Examples
    --------
    >>> require_vector([0, 3e300, 4e300], "axis", direction=True)
    (0.0, 0.6, 0.8)
    >>> require_vector([1, 2], "point")
    Traceback (most recent call last):
    mobility.errors.MechanismError: point: expected a list of 3 numbers, got 2
    """
    plain = type(value) in (tuple, list) and len(value) == 3 and all(type(x) in (float, int) for x in value)  # no bool, no text
    if plain and not direction:
        try:  # the common case, without numpy's per-call overhead
            x, y, z = (float(x) for x in value)
        except OverflowError:
            raise MechanismError(key, "expected 3 finite numbers, got an integer too large for a float") from None
        if math.isfinite(x) and math.isfinite(y) and math.isfinite(z):
            return (x, y, z)
    items = value.tolist() if isinstance(value, np.ndarray) and value.dtype.kind in "bUSO" else value
    if not plain and isinstance(items, (list, tuple)) and any(isinstance(x, (bool, np.bool_)) or (isinstance(x, str) and (not x.isascii() or "_" in x)) for x in items):
        raise MechanismError(key, f"expected a list of 3 numbers (not true or false, digits in ASCII, no '_'), got {shown_argument(value)}")
    try:
        arr = np.asarray(value, dtype=float)
    except OverflowError:
        raise MechanismError(key, "expected 3 finite numbers, got an integer too large for a float") from None
    except (TypeError, ValueError):
        raise MechanismError(key, f"expected a list of 3 numbers, got {value!r}") from None
    if arr.shape != (3,):
        n = arr.size if arr.ndim == 1 else "a nested list" if arr.ndim > 1 else shown_argument(value)
        raise MechanismError(key, f"expected a list of 3 numbers, got {n}")
    if not np.all(np.isfinite(arr)):
        raise MechanismError(key, f"expected 3 finite numbers, got {value!r}")
    if direction:
        largest = max(abs(x) for x in arr.tolist())
        if largest == 0.0:
            raise MechanismError(key, "expected a non-zero direction, got [0, 0, 0]")
        if not 1e-140 < largest < 1e140:  # its square could underflow or overflow: scale it by a power of two first (exact)
            arr = arr * binary_scale(arr)
        x, y, z = arr.tolist()
        size = math.hypot(x, y, z)  # the same on every machine (``arr @ arr`` sums in the order of the BLAS kernel the CPU picks)
        if abs(size - 1.0) > UNIT_ROUND_OFF:  # a direction already of unit length to round-off is kept as written: it reads back to the bit
            x, y, z = x / size, y / size, z / size
        return (x, y, z)
    return (float(arr[0]), float(arr[1]), float(arr[2]))


def _listed(value: Any) -> Any:
    """``value`` as a tuple when it is iterable (a generator too), else as it is (for :func:`require_vector` to refuse)."""
    return tuple(value) if isinstance(value, Iterable) and not isinstance(value, (str, bytes, Mapping)) else value


def require_integer(value: Any, expected: str, *, caller: str = "", argument: str = "", low: int | None = None, high: int | None = None,
                    error: type[RequestError] = RequestError) -> int:
    """``value`` as an ``int`` when it is an integer (``int``, a numpy integer, anything with ``__index__``; not a bool) from ``low`` to ``high``, else ``error`` with the fields given.

    Examples
    --------
    >>> require_integer(np.int64(3), "an integer from 1 to 8", caller="view", argument="max_poses", low=1, high=8)
    3
    >>> require_integer(9, "an integer from 1 to 8", caller="view", argument="max_poses", low=1, high=8)
    Traceback (most recent call last):
    mobility.errors.RequestError: view: max_poses: expected an integer from 1 to 8, got 9
    >>> require_integer(3.0, "an integer")
    Traceback (most recent call last):
    mobility.errors.RequestError: expected an integer, got 3.0
    """
    if not isinstance(value, (bool, np.bool_)):
        try:
            number = operator.index(value)
        except TypeError:
            pass
        else:
            if (low is None or number >= low) and (high is None or number <= high):
                return number
    raise error(caller=caller, argument=argument, expected=expected, got=shown_argument(value))


def require_real(value: Any, expected: str, *, caller: str = "", argument: str = "", positive: bool = False) -> float:
    """``value`` as a finite ``float`` when it is a real number (``int``, ``float``, a numpy number; not a bool), positive if asked, else a :class:`~mobility.errors.RequestError` with the fields given.

    Examples
    --------
    >>> require_real(np.float32(0.5), "a finite positive length", caller="assemble_pkm", argument="height", positive=True)
    0.5
    >>> require_real(True, "a finite number of degrees", caller="assemble_pkm", argument="twist_deg")
    Traceback (most recent call last):
    mobility.errors.RequestError: assemble_pkm: twist_deg: expected a finite number of degrees, got True
    >>> require_real(10**400, "a finite number")
    Traceback (most recent call last):
    mobility.errors.RequestError: expected a finite number, got 1000000000000000000000000000000000000...
    """
    if not isinstance(value, (bool, np.bool_)) and isinstance(value, numbers.Real):
        try:
            number = float(value)
        except OverflowError:  # an integer beyond the floats
            number = math.inf
        if math.isfinite(number) and (number > 0.0 or not positive):
            return number
    raise RequestError(caller=caller, argument=argument, expected=expected, got=shown_argument(value))


def require_bool(value: Any, *, caller: str = "", argument: str = "", got: str | None = None) -> bool:
    """``value`` as a ``bool`` when it is one (``numpy.True_`` too; not ``1``), else a :class:`~mobility.errors.RequestError` (``got``: how the value is shown, default its ``repr``).

    Examples
    --------
    >>> require_bool(np.True_, caller="plot_mechanism", argument="labels")
    True
    >>> require_bool(1, caller="plot_mechanism", argument="labels")
    Traceback (most recent call last):
    mobility.errors.RequestError: plot_mechanism: labels: expected True or False, got 1
    """
    if not isinstance(value, (bool, np.bool_)):
        raise RequestError(caller=caller, argument=argument, expected="True or False", got=shown_argument(value) if got is None else got)
    return bool(value)


def _not_bool(value: Any) -> Any:
    """``value``, unless it is a bool (``True`` is not the number 1 here): then a ``TypeError``, as ``float`` raises for what is not a number."""
    if isinstance(value, (bool, np.bool_)):
        raise TypeError(f"expected a number, got {value!r}")
    return value


def number_from_text(text: str) -> float:
    """The number written in ``text``, as ``float`` reads it, but in ASCII only and without ``_`` (``float`` reads ``"1_0"`` as 10).

    The one reader of a number written as text (an option, an environment
    variable): ``float`` alone reads the digits of every script (``"١"`` is 1).
    Anything else raises ``ValueError``.

    Examples
    --------
    >>> number_from_text(" 1e-9 ")
    1e-09
    >>> number_from_text("\u0661")
    Traceback (most recent call last):
    ValueError: expected a number written in ASCII digits, got '\u0661'
    """
    return float(_in_ascii(text, "a number"))


def integer_from_text(text: str) -> int:
    """The integer written in ``text``, as ``int`` reads it (base 10), but in ASCII only (see :func:`number_from_text`).

    Examples
    --------
    >>> integer_from_text("20000")
    20000
    >>> integer_from_text("\u0661\u0660")
    Traceback (most recent call last):
    ValueError: expected an integer written in ASCII digits, got '\u0661\u0660'
    """
    return int(_in_ascii(text, "an integer"))


def _in_ascii(text: str, what: str) -> str:
    """``text`` when it is ASCII without ``_`` (which ``float`` and ``int`` skip), else a ``ValueError`` saying ``what`` it should be.

    Examples
    --------
    >>> _in_ascii("1_0e-9", "a number")
    Traceback (most recent call last):
    ValueError: expected a number written in ASCII digits (no '_'), got '1_0e-9'
    """
    if not text.isascii() or "_" in text:
        underscore = " (no '_')" if "_" in text else ""
        raise ValueError(f"expected {what} written in ASCII digits{underscore}, got {shown_argument(text)}")
    return text


def require_instance(value: object, cls: type[_T], caller: str, reader: str) -> _T:
    """``value`` when it is a ``cls``, else a :class:`~mobility.errors.RequestError` naming ``caller`` and where a ``cls`` comes from (``reader``).

    Examples
    --------
    >>> require_instance(3, str, "label", "str()")
    Traceback (most recent call last):
    mobility.errors.RequestError: label: expected a str (from str() or built in code), got int
    """
    if not isinstance(value, cls):
        raise RequestError(caller=caller, expected=f"a {cls.__name__} (from {reader} or built in code)", got=type(value).__name__)
    return value


# The checks every graph of bodies shares (the mechanism model and the flexure documents).


def require_graph_names(graph: Any, node: str) -> None:
    """``graph.name``, ``.ground`` and ``.end_effector`` must be non-empty strings (``node``: "link", "body").

    Examples
    --------
    >>> from types import SimpleNamespace
    >>> require_graph_names(SimpleNamespace(name="m", ground="g", end_effector=""), "link")
    Traceback (most recent call last):
    mobility.errors.MechanismError: end_effector: expected the name of a link (a non-empty string), got ''
    """
    if not isinstance(graph.name, str) or not graph.name:  # a title, which a robot file may take from its file's name: held to the rule of names where a file writes it
        raise MechanismError("name", f"expected a non-empty string, got {graph.name!r}")
    for key in ("ground", "end_effector"):
        require_name(getattr(graph, key), key, f"the name of a {node} (a non-empty string)")


def require_name(value: Any, key: str, expected: str) -> None:
    """``value`` must be a name: a non-empty string without control, format or line-break characters (:func:`~mobility.errors.name_problem`).

    ``key`` is the error's key (``"links[0]"``), ``expected`` what a name there
    is (``"a frame name"``), said when ``value`` is not a non-empty string.

    Examples
    --------
    >>> require_name("hip\\tleft", "name", "a joint name")
    Traceback (most recent call last):
    mobility.errors.MechanismError: name: a tab '\\t' (U+0009) is not allowed in a name
    """
    if type(value) is str and value.isprintable() and value:  # the common case, at one call's cost
        return
    if not isinstance(value, str) or not value:
        raise MechanismError(key, f"expected {expected}, got {value!r}")
    problem = name_problem(value)
    if problem is not None:
        raise MechanismError(key, problem)


def joint_names(value: Any, key: str) -> list[str]:
    """``value`` as a list of joint names: a list, tuple or other iterable of strings (not one string).

    Examples
    --------
    >>> joint_names(("P1", "P2"), "actuated")
    ['P1', 'P2']
    >>> joint_names("P1", "actuated")
    Traceback (most recent call last):
    mobility.errors.MechanismError: actuated: expected a sequence of joint names, got the string 'P1' (write ['P1'])
    """
    if isinstance(value, str):
        raise MechanismError(key, f"expected a sequence of joint names, got the string {value!r} (write [{value!r}])")
    try:
        names = list(value)
    except TypeError:
        raise MechanismError(key, f"expected a sequence of joint names, got {type(value).__name__}") from None
    for name in names:
        if not isinstance(name, str):
            raise MechanismError(key, f"expected joint names (strings), got {name!r}")
    return names


def require_no_repeats(names: Iterable[str], key: str) -> None:
    """No name of ``names`` (a choice of inputs, say) is given twice; ``key`` names the option or argument.

    Examples
    --------
    >>> require_no_repeats(["P1", "P2", "P1"], "actuated")
    Traceback (most recent call last):
    mobility.errors.MechanismError: actuated: 'P1' is given twice; name each input once
    """
    seen: set[str] = set()
    for name in names:
        if name in seen:
            raise MechanismError(key, f"{name!r} is given twice; name each input once")
        seen.add(name)


def require_unique_names(items: Iterable[Any], key: str, what: str) -> None:
    """No two of ``items`` (each with a ``name``) share a name; ``key`` is their list's key, ``what`` their kind.

    Examples
    --------
    >>> from types import SimpleNamespace as N
    >>> require_unique_names([N(name="A"), N(name="B"), N(name="A")], "joints", "joint")
    Traceback (most recent call last):
    mobility.errors.MechanismError: joints[2].name: duplicate joint name 'A' (first used by joints[0])
    """
    seen: dict[str, int] = {}
    for i, item in enumerate(items):
        first = seen.setdefault(item.name, i)
        if first != i:
            raise MechanismError(f"{key}[{i}].name", f"duplicate {what} name {item.name!r} (first used by {key}[{first}])")


def require_ground_and_end_effector(graph: Any, nodes: Iterable[str], node: str, edge: str) -> None:
    """The ground and the end effector of ``graph`` are two different ``nodes`` (joined by some ``edge``).

    Examples
    --------
    >>> from types import SimpleNamespace as N
    >>> require_ground_and_end_effector(N(ground="g", end_effector="e"), {"g", "l"}, "link", "joint")
    Traceback (most recent call last):
    mobility.errors.MechanismError: end_effector: link 'e' is not joined by any joint
    """
    for key in ("ground", "end_effector"):
        if getattr(graph, key) not in nodes:
            raise MechanismError(key, f"{node} {getattr(graph, key)!r} is not joined by any {edge}")
    if graph.end_effector == graph.ground:
        raise MechanismError("end_effector", "the end effector must differ from the ground")
