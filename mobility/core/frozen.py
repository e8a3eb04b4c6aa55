"""Read-only arrays for the frozen results: :func:`read_only`, :class:`ReadOnlyArrays`, :func:`read_only_cached_property`.

A frozen dataclass forbids assigning its fields, not writing into its numpy
arrays; the results derive from :class:`ReadOnlyArrays` so that every array
they hold or compute is read-only, also after a pickle round trip or a deep
copy (numpy unpickles arrays writable).  Numpy and the standard library only.
"""

from __future__ import annotations

from dataclasses import fields as dataclass_fields
from functools import cached_property, wraps
from typing import Any, Callable, TypeVar

import numpy as np

__all__ = ["read_only", "read_only_cached_property", "ReadOnlyArrays"]

_T = TypeVar("_T")


def _sealed(array: np.ndarray) -> bool:
    """True when nothing can write into ``array``'s data: it and every array it views read-only, over read-only memory."""
    base: object = array
    while isinstance(base, np.ndarray):
        if base.flags.writeable:
            return False
        base = base.base
    if base is None:
        return True
    try:
        return memoryview(base).readonly  # type: ignore[arg-type]
    except TypeError:  # memory that is not a buffer: it may change
        return False


def read_only(value: _T, *, copy: bool = True) -> _T:
    """``value`` with every ndarray in it read-only: an array, or a tuple (named or not) holding some, at any depth.

    ``copy`` true (an array the caller may share): one that something could
    still write into is replaced by a read-only copy.  False (arrays just
    computed or unpickled): every array and every array it views is made
    read-only in place.  Other values are returned as they are.

    Examples
    --------
    >>> mine = np.zeros(3)
    >>> kept = read_only((mine, "x"))
    >>> kept[0].flags.writeable, mine.flags.writeable, kept[1]
    (False, True, 'x')
    >>> kept[0][0] = 1.0
    Traceback (most recent call last):
    ValueError: assignment destination is read-only
    """
    if isinstance(value, np.ndarray):
        if not copy:
            base: object = value
            while isinstance(base, np.ndarray):
                base.setflags(write=False)
                base = base.base
            return value
        if _sealed(value):
            return value
        out = value.copy(order="K")
        out.setflags(write=False)
        return out
    if isinstance(value, tuple) and value:
        items = [read_only(x, copy=copy) for x in value]
        if all(a is b for a, b in zip(items, value)):
            return value
        make = getattr(type(value), "_make", None)  # a named tuple
        return make(items) if make is not None else tuple(items)  # type: ignore[return-value]
    return value


def read_only_cached_property(func: Callable[[Any], _T]) -> cached_property:
    """:func:`functools.cached_property` whose value has its arrays read-only (:func:`read_only`, copying shared ones).

    Examples
    --------
    >>> class Grid:
    ...     @read_only_cached_property
    ...     def values(self):
    ...         return np.arange(3.0)
    >>> g = Grid()
    >>> g.values.flags.writeable, g.values is g.values
    (False, True)
    """

    @wraps(func)
    def compute(self: Any) -> _T:
        return read_only(func(self))

    return cached_property(compute)


_PLAIN_TYPES = frozenset(f"{t}{none}" for t in ("int", "float", "str", "bool") for none in ("", " | None"))
"""Annotations of the fields that hold no array (a result's many counts and names are not looked at)."""


def _may_hold_arrays(cls: type) -> tuple[str, ...]:
    """The fields of dataclass ``cls`` whose annotation is not one of :data:`_PLAIN_TYPES` (found once per class)."""
    names = cls.__dict__.get("_array_fields")
    if names is None:
        names = tuple(f.name for f in dataclass_fields(cls) if (f.type if isinstance(f.type, str) else getattr(f.type, "__name__", "")) not in _PLAIN_TYPES)
        cls._array_fields = names  # type: ignore[attr-defined]
    return names


class ReadOnlyArrays:
    """Base of the frozen result dataclasses: every ndarray they hold is read-only, also after a pickle round trip.

    Each field goes through :func:`read_only` on construction (a subclass's
    own ``__post_init__`` calls this one); unpickling and :func:`copy.deepcopy`
    freeze the restored arrays again (``__setstate__``).

    Examples
    --------
    >>> import copy, numpy as np
    >>> from dataclasses import dataclass
    >>> @dataclass(frozen=True)
    ... class Line(ReadOnlyArrays):
    ...     point: np.ndarray
    ...     direction: np.ndarray
    ...     name: str
    >>> mine = np.zeros(3)
    >>> line = Line(mine, np.array([0.0, 0.0, 1.0]), "z")
    >>> line.point.flags.writeable, mine.flags.writeable, line.point is mine
    (False, True, False)
    >>> again = copy.deepcopy(line)  # a pickle round trip likewise
    >>> again.direction.flags.writeable, again.direction.tolist()
    (False, [0.0, 0.0, 1.0])
    """

    __slots__ = ()

    def __post_init__(self) -> None:
        values = vars(self)
        for name in _may_hold_arrays(type(self)):
            value = values.get(name)
            if isinstance(value, (np.ndarray, tuple)):
                frozen = read_only(value)
                if frozen is not value:
                    values[name] = frozen  # past the frozen __setattr__, as the dataclass's own __init__ does

    def __setstate__(self, state: dict[str, Any]) -> None:
        for value in state.values():
            read_only(value, copy=False)  # the arrays of a pickle (or of a deep copy) are new: frozen in place
        vars(self).update(state)
