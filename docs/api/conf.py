"""Sphinx configuration of the API reference, built from the package's numpydoc docstrings.

Build from the repository root (``.ci/docs`` does, in CI)::

    python -m sphinx -b html -W --keep-going -n docs/api build/api

(``.ci/docs`` adds ``-E``: every page read afresh, so that no warning stays hidden in a cached one.)

``-W`` turns every warning into an error and ``-n`` (nitpicky) makes every
cross-reference that leads nowhere a warning, so a broken docstring or a
reference to a name that does not exist fails the build.  No inventory of
another project can be fetched (the build runs offline): the references to
Python's, numpy's and the other dependencies' types are listed below, by
package, as the only ones left unresolved.
"""

import importlib
import re
import sys
import types
import warnings
from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT))

import mobility  # noqa: E402

project = "mobility"
author = "the mobility authors"
copyright = "the mobility authors, BSD-3-Clause"
release = version = mobility.__version__

extensions = [
    "sphinx.ext.autodoc",
    "sphinx.ext.autosummary",
    "sphinx.ext.mathjax",
    "numpydoc",
]

exclude_patterns = ["_build"]
html_theme = "alabaster"
html_static_path: list[str] = []

autosummary_generate = False
autodoc_member_order = "bysource"
autodoc_default_options = {"show-inheritance": True}
numpydoc_show_class_members = False
numpydoc_class_members_toctree = False
# numpydoc's checks of a docstring's structure, warnings (so errors) too: an unknown section (a misspelt
# "Return"), sections out of order, a documented parameter the signature does not have (renamed or
# removed), parameters out of order, a parameter line without the space before its colon.
numpydoc_validation_checks = {"GL06", "GL07", "PR02", "PR03", "PR10"}
# A constant that is an instance (of a dataclass) is validated against its class's docstring, with no
# signature to hold the parameters: its class is validated where it is documented.
numpydoc_validation_exclude = {r"\.DEFAULT_TOLERANCE$"}

nitpicky = True
default_role = "py:obj"


def _module_pages(app: Any) -> None:
    """Write one page per module of ``mobility`` into ``generated/``: the module's docstring and its
    members (its ``__all__``); a package's page lists the names it exports and its modules.

    Written here rather than by autosummary's recursion, which takes a submodule for the function of
    the same name that its package exports (``mobility.jacobians.jacobian``).
    """
    import pkgutil

    out = Path(app.srcdir) / "generated"
    out.mkdir(exist_ok=True)
    names = ["mobility"] + [info.name for info in pkgutil.walk_packages(mobility.__path__, "mobility.")
                            if not any(part.startswith("_") for part in info.name.split("."))]
    for name in names:
        module = importlib.import_module(name)
        title = f"``{name}``"
        lines = [title, "=" * len(title), "", f".. automodule:: {name}", "   :members:", "   :show-inheritance:"]
        if hasattr(module, "__path__"):
            lines.append("   :ignore-module-all:")
            exported = list(getattr(module, "__all__", []))
            if exported:
                lines += ["", ".. rubric:: Exported names", "",
                          f"Defined in the modules below; ``from {name} import NAME`` works for each.", "",
                          ".. autosummary::", ""] + [f"   {item}" for item in exported]
            children = [n for n in names if n.rpartition(".")[0] == name]
            if children:
                lines += ["", ".. rubric:: Modules", "", ".. toctree::", "   :maxdepth: 1", ""] + [f"   {child}" for child in children]
        text = "\n".join(lines) + "\n"
        page = out / f"{name}.rst"
        if not page.exists() or page.read_text() != text:
            page.write_text(text)
    for page in out.glob("*.rst"):
        if page.stem not in names:  # a module since removed or renamed
            page.unlink()
    _DEFINED.clear()


# Names of Python and of the dependencies that a docstring or a type hint mentions: with no inventory
# of theirs to link to, these (and only these) stay plain text.  A name of ``mobility`` is never here.
_EXTERNAL_MODULES = (
    "numpy", "np", "scipy", "networkx", "yaml", "plotly", "matplotlib", "mpl_toolkits", "mujoco", "dask",
    "tqdm", "pytest", "_pytest", "IPython", "PIL", "playwright",
    "typing", "collections", "pathlib", "os", "io", "re", "types", "functools", "xml", "argparse", "math",
    "multiprocessing", "concurrent", "copy", "dataclasses", "enum", "fractions", "itertools", "json", "sys", "warnings",
)
_BUILTINS = (
    "object", "type", "None", "NoneType", "bool", "int", "float", "complex", "str", "bytes", "tuple", "list",
    "dict", "set", "frozenset", "range", "slice", "callable", "Ellipsis", "NotImplemented",
    "Exception", "ValueError", "TypeError", "KeyError", "OSError", "RuntimeError", "ImportError", "AttributeError",
    "ArithmeticError", "UnicodeError", "Warning", "UserWarning", "RuntimeWarning",
)
nitpick_ignore_regex = [
    (r"py:.*", r"(%s)(\..*)?" % "|".join(_EXTERNAL_MODULES)),
    (r"py:.*", r"(%s)" % "|".join(_BUILTINS)),
    # written as bare names in annotations that Python cannot evaluate (imported for type checking only)
    (r"py:class", r"Path|Figure|Axes"),
    # a type alias (int or array) that annotations show by its name; documented as data of core.screw_systems
    (r"py:class", r"PerPose"),
]


_MISSING = object()
"""What :func:`_python_object` returns for a name that leads nowhere."""

_DEFINED: dict[tuple[int, str], str] = {}
""":func:`_defined_names` of this build (object identities hold for one process only: never pickled)."""


def _python_object(name: str) -> Any:
    """The object a dotted ``mobility`` name leads to (importing its modules), or ``_MISSING``."""
    parts = name.split(".")
    for cut in range(len(parts), 0, -1):
        try:
            value = importlib.import_module(".".join(parts[:cut]))
        except ImportError:
            continue
        try:
            for part in parts[cut:]:
                value = getattr(value, part)
        except AttributeError:
            return _MISSING
        return value
    return _MISSING


def _defined_names(env: Any) -> dict[tuple[int, str], str]:
    """Each documented object of ``mobility`` by (identity, last name part): its documented (defining) name."""
    found: dict[tuple[int, str], str] = {}
    for name, entry in env.get_domain("py").objects.items():
        if name.startswith("mobility.") and not entry.aliased:
            value = _python_object(name)
            if value is not _MISSING:
                found.setdefault((id(value), name.rpartition(".")[2]), name)
    return found


def _documented(env: Any, name: str) -> str | None:
    """The name under which the object ``name`` leads to is documented, or ``None``.

    A name documented as written is its own answer; a re-exported one (``mobility.analyze``,
    ``mobility.actuation.check_actuation``) answers the defining module's name, where it is documented.
    """
    entry = env.get_domain("py").objects.get(name)
    if entry is not None and not entry.aliased:
        return name
    value = _python_object(name)
    if value is _MISSING:
        return None
    if not _DEFINED:
        _DEFINED.update(_defined_names(env))
    return _DEFINED.get((id(value), name.rpartition(".")[2]))


def _ours(value: Any) -> bool:
    """Whether a value found in a module of ``mobility`` is the package's own (not an imported module,
    class or function of Python or of a dependency)."""
    if isinstance(value, types.ModuleType):
        return value.__name__.startswith("mobility")
    module = getattr(value, "__module__", None)
    return not isinstance(module, str) or module.startswith("mobility")


def _owner(env: Any, name: str) -> str | None:
    """The documented object nearest above ``name`` that really has it as a member: a class for its
    dataclass field (``Tolerance.closure``), a module for a constant without a docstring or a private
    helper (``mobility.sweeps.steps.RETURN_STEPS``, ``_walks_back``).  ``None`` when a step of
    the name does not exist."""
    parent, _, member = name.rpartition(".")
    if not parent.startswith("mobility"):
        return None
    owner = _python_object(parent)
    if owner is _MISSING:
        return None
    fields = set(getattr(owner, "__dataclass_fields__", {})) | set(getattr(owner, "__annotations__", {}))
    if member not in fields:
        value = getattr(owner, member, _MISSING)
        if value is _MISSING or not _ours(value):
            return None
    return _documented(env, parent) or _owner(env, parent)


def _resolve_exported(app: Any, env: Any, node: Any, contnode: Any) -> Any:
    """Resolve what the Python domain could not, to the place the object is documented.

    A re-exported name (``mobility.analyze``, or ``Result`` inside ``mobility``) leads to the module
    defining it; a dataclass field, a constant without a docstring or a private helper leads to the
    class or module that has it.  Every step of the name must exist in the package: a reference to a
    name that does not exist (misspelt, moved, removed) stays unresolved, and the nitpicky build fails
    on it.
    """
    if node.get("refdomain") != "py":
        return None
    target = node.get("reftarget", "")
    if " | " in target:
        # a union written in a string (a forward reference, ``"CheckResult | None"``): shown as
        # written when every member of it resolves
        members = [member.strip() for member in target.split("|")]
        return contnode if all(member == "None" or _found(env, node, member) for member in members) else None
    found = _found(env, node, target)
    if found is None or found == target:
        return None
    return env.get_domain("py").resolve_xref(env, node["refdoc"], app.builder, "obj", found, node, contnode)


def _found(env: Any, node: Any, target: str) -> str | None:
    """Where ``target``, read in the module (and class) of the reference, is documented, or ``None``."""
    module, cls = node.get("py:module"), node.get("py:class")
    scopes = [target] if target.startswith("mobility") else []
    if module and module.startswith("mobility"):
        if cls:
            scopes.append(f"{module}.{cls}.{target}")
        scopes.append(f"{module}.{target}")
    for scope in scopes:
        found = _documented(env, scope) or _owner(env, scope)
        if found is not None:
            return found
    return None


def _signature(app: Any, what: str, name: str, obj: Any, options: Any, signature: str | None, return_annotation: str | None) -> Any:
    """Two signatures Sphinx cannot read as written: a type alias (``Motion = tuple[ndarray, ndarray]``,
    which numpydoc takes for a class and fails on) has none, and a dataclass field's ``default_factory``
    shows as ``...`` rather than ``<factory>`` (which is not Python, so Sphinx split the signature at
    every comma, inside brackets too)."""
    if isinstance(obj, types.GenericAlias):
        return ()  # a result (numpydoc's is not asked) that gives no signature
    if signature and "<factory>" in signature:
        return re.sub(r"=\s*<factory>", "=...", signature), return_annotation
    return None


def _numpydoc_problems() -> None:
    """numpydoc reports what it cannot parse (an unknown section such as a misspelt ``Return``, an
    underline of the wrong length) as Python warnings, which Sphinx would print and let pass: each one
    becomes a Sphinx warning here, so an error of the build, every time it occurs."""
    from sphinx.util import logging as sphinx_logging

    logger = sphinx_logging.getLogger("numpydoc")
    shown = warnings.showwarning

    def show(message: Any, category: type, filename: str, lineno: int, file: Any = None, line: str | None = None) -> None:
        if "numpydoc" in Path(filename).parts or "numpydoc" in filename:
            logger.warning("%s", " ".join(str(message).split()))
        else:
            shown(message, category, filename, lineno, file, line)

    warnings.filterwarnings("always", category=UserWarning, module=r"numpydoc\..*")
    warnings.showwarning = show


def setup(app: Any) -> None:
    _numpydoc_problems()
    app.connect("autodoc-process-signature", _signature, priority=400)
    app.connect("builder-inited", _module_pages)
    app.connect("missing-reference", _resolve_exported)
