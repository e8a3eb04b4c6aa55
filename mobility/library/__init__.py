"""The bundled library: the classic mechanisms and the flexure examples, shipped inside the package.

``mechanisms/`` holds the classic mechanisms (each with its ``expected``
block and its source), ``examples/flexure/`` the flexure examples; in a clone
the folders of the same names at its root link to them, so
``mechanisms/3prs.yaml`` names the same file.  ``mobility check --library``
checks them all.

Examples
--------
>>> import mobility
>>> mobility.library.path("3prs").name
'3prs.yaml'
>>> mobility.analyze(mobility.load(mobility.library.path("bennett"))).pattern
'1R'
>>> len(names()), names()[:3], flexure_names()
(64, ('3crr', '3prs', '3prs_tilted'), ('three_rod',))
>>> [folder.name for folder in folders()]
['mechanisms', 'flexure']
>>> path("benett")
Traceback (most recent call last):
    ...
mobility.errors.RequestError: library.path: no file named 'benett' in the bundled library (did you mean 'bennett'?); \
names: 3crr, 3prs, 3prs_tilted, 3rps, 3ruu, 3upu_singular, 3upu_wrist, 4puu, 4puu_singular, 4ruu_schoenflies, 6sps, 6ups, \
... (65 in all)
"""

from __future__ import annotations

from pathlib import Path

from ..errors import RequestError, clipped, did_you_mean, name_list

__all__ = ["MECHANISMS", "FLEXURE", "folders", "names", "flexure_names", "path", "paths"]

MECHANISMS = Path(__file__).resolve().parent / "mechanisms"
"""The folder of the classic mechanisms (``mechanisms/`` in a clone): one YAML file each."""

FLEXURE = Path(__file__).resolve().parent / "examples" / "flexure"
"""The folder of the flexure examples (``examples/flexure/`` in a clone): one flexure document each."""

SUFFIX = ".yaml"
"""The suffix of every bundled file; a name is the file's name without it."""


def folders() -> tuple[Path, Path]:
    """The two folders of the library, :data:`MECHANISMS` and :data:`FLEXURE`: what ``mobility check --library`` checks.

    Examples
    --------
    >>> all(folder.is_dir() for folder in folders())
    True
    """
    return (MECHANISMS, FLEXURE)


def _stems(folder: Path) -> tuple[str, ...]:
    return tuple(sorted(p.name.removesuffix(SUFFIX) for p in folder.glob(f"*{SUFFIX}") if p.is_file()))


def names() -> tuple[str, ...]:
    """The names of the classic mechanisms, sorted: ``"3prs"`` for ``mechanisms/3prs.yaml``.

    Examples
    --------
    >>> "bennett" in names() and "sarrus" in names()
    True
    """
    return _stems(MECHANISMS)


def flexure_names() -> tuple[str, ...]:
    """The names of the flexure examples, sorted (read them with :func:`mobility.load_flexure`).

    Examples
    --------
    >>> import mobility
    >>> mobility.load_flexure(path(flexure_names()[0])).name
    'three-rod spherical flexure (actuation example)'
    """
    return _stems(FLEXURE)


def paths() -> tuple[Path, ...]:
    """Every file of the library: the classic mechanisms, then the flexure examples, each sorted by name.

    Examples
    --------
    >>> len(paths()), paths()[-1].name
    (65, 'three_rod.yaml')
    """
    return tuple(MECHANISMS / f"{n}{SUFFIX}" for n in names()) + tuple(FLEXURE / f"{n}{SUFFIX}" for n in flexure_names())


def path(name: str) -> Path:
    """The bundled file (absolute, inside the installed package) of a mechanism or flexure example, by its name (``"3prs"``; ``"3prs.yaml"`` too).

    Raises
    ------
    RequestError
        ``name`` is not a string or names no file of the library (the message suggests the closest name).

    Examples
    --------
    >>> path("sarrus.yaml") == path("sarrus") == MECHANISMS / "sarrus.yaml"
    True
    >>> path("three_rod").parent == FLEXURE
    True
    """
    if not isinstance(name, str):
        raise RequestError(caller="library.path", expected="a name (str)", got=type(name).__name__)
    stem = name.removesuffix(SUFFIX)
    for folder, known in ((MECHANISMS, names()), (FLEXURE, flexure_names())):
        if stem in known:
            return folder / f"{stem}{SUFFIX}"
    every = names() + flexure_names()
    raise RequestError(f"no file named {clipped(name)!r} in the bundled library{did_you_mean(stem, every)}; names: {name_list(every)}", caller="library.path")
