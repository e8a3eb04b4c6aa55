"""Sphinx configuration of the API reference, built from the package's numpydoc docstrings.

Build from the repository root (``.ci/docs`` does, in CI)::

    python -m sphinx -b html -W --keep-going -n docs/api build/api

``-W`` turns every warning into an error and ``-n`` (nitpicky) makes every
cross-reference that leads nowhere a warning, so a broken docstring or a
reference to a name that does not exist fails the build.  No inventory of
another project can be fetched (the build runs offline): the references to
Python's, numpy's and the other dependencies' types are listed below, by
package, as the only ones left unresolved.
"""

import importlib
import sys
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

# Names of Python and of the dependencies that a docstring or a type hint mentions: with no inventory
# of theirs to link to, these (and only these) stay plain text.  A name of ``mobility`` is never here.
_EXTERNAL_MODULES = (
    "numpy", "np", "scipy", "networkx", "yaml", "plotly", "matplotlib", "mpl_toolkits", "mujoco", "dask",
    "tqdm", "pytest", "_pytest", "IPython", "PIL", "playwright",
    "typing", "collections", "pathlib", "os", "io", "re", "types", "functools", "xml", "argparse", "math",
    "multiprocessing", "concurrent", "dataclasses", "enum", "fractions", "itertools", "json", "sys", "warnings",
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
]


def _python_object(name: str) -> Any:
    """The object a dotted ``mobility`` name leads to (importing its modules), or ``None``."""
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
            return None
        return value
    return None


def _defined_names(env: Any) -> dict[tuple[int, str], str]:
    """Each documented object of ``mobility`` by (identity, last name part): its documented (defining) name."""
    found: dict[tuple[int, str], str] = {}
    for name, entry in env.get_domain("py").objects.items():
        if name.startswith("mobility.") and not entry.aliased:
            value = _python_object(name)
            if value is not None:
                found.setdefault((id(value), name.rpartition(".")[2]), name)
    return found


def _resolve_exported(app: Any, env: Any, node: Any, contnode: Any) -> Any:
    """A reference to a re-exported name (``mobility.analyze``, ``mobility.actuation.check_actuation``,
    or ``Result`` inside ``mobility``) leads to the one place it is documented: the module defining it.

    Only a name that imports as the very object documented there resolves; any other reference stays
    unresolved, and the nitpicky build fails on it.
    """
    if node.get("refdomain") != "py":
        return None
    target = node.get("reftarget", "")
    scopes = [target] if target.startswith("mobility.") else []
    for prefix in (node.get("py:class"), node.get("py:module")):
        if prefix and prefix.startswith("mobility"):
            scopes.append(f"{node.get('py:module')}.{prefix}.{target}" if prefix == node.get("py:class") and node.get("py:module") else f"{prefix}.{target}")
    if not scopes:
        return None
    if not hasattr(env, "_mobility_defined"):
        env._mobility_defined = _defined_names(env)
    domain = env.get_domain("py")
    for scope in scopes:
        value = _python_object(scope)
        if value is None:
            continue
        defined = env._mobility_defined.get((id(value), scope.rpartition(".")[2]))
        if defined is not None and defined != scope:
            node["reftarget"] = defined
            return domain.resolve_xref(env, node["refdoc"], app.builder, node["reftype"], defined, node, contnode) \
                or domain.resolve_any_xref and domain.resolve_xref(env, node["refdoc"], app.builder, "obj", defined, node, contnode)
    return None


def setup(app: Any) -> None:
    app.connect("builder-inited", _module_pages)
    app.connect("missing-reference", _resolve_exported)
