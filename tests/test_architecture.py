"""The architecture, as the folders of the package show it, checked on every module's imports.

Data flows one way: files -> model -> topology -> screw systems -> result ->
report/CLI.  ``core`` knows nothing of files or features; ``io`` (the loaders)
knows the model and nothing of screws; the features sit side by side on the
core and share only public names; ``report`` formats what they return; ``cli``
only parses arguments.
"""

import ast
import importlib
import inspect
import pkgutil
from pathlib import Path

import pytest

import mobility

PACKAGE = Path(mobility.__file__).resolve().parent

# Each folder and what it may import, one line each ("core.model": that module of core only).
ALLOWED = {
    "errors": "",
    "outputs": "",
    "core": "errors",
    "io": "errors core.model core.expected core.validation core.transforms core.tolerance",
    "finite": "errors core",
    "actuation": "errors core",
    "flexure": "errors core io actuation",
    "synthesis": "errors core io outputs",
    "jacobians": "errors core",
    "sweeps": "errors core actuation transmission",
    "transmission": "errors core actuation",
    "report": "errors core finite actuation flexure synthesis jacobians sweeps testing outputs",
    "view": "errors core report sweeps outputs",
    "testing": "errors core io finite actuation flexure",
    "library": "errors",
    "cli": "__init__ errors core io finite actuation flexure synthesis jacobians sweeps transmission report view testing library outputs",
    "__init__": "errors core io finite actuation flexure synthesis jacobians sweeps transmission report view testing library outputs",
    "__main__": "cli",
}

# Inside the core, data flows by layer: a module imports only modules of lower layers.
CORE_LAYERS = {
    "tolerance": 0, "transforms": 0, "frozen": 0, "couplings": 0,
    "validation": 1, "linalg": 1, "finite_screws": 1,
    "expected": 2,
    "model": 3,
    "screws": 4, "topology": 4,
    "joint_screws": 5,
    "screw_systems": 6, "loop_closure": 6, "canonical": 6,
    "kinematics": 6,  # the one kinematics and Newton's method, of one pose or a stack of them (sweeps use it)
    "result": 7, "poses": 7,
    "analysis": 8,
    "closures": 9,
}
# ... and screw algebra knows no model, the topology no geometry.
CORE_APART = {
    "screws": {"model", "expected", "topology", "joint_screws"},
    "canonical": {"model", "expected", "topology", "joint_screws"},
}


def folder_of(path: Path) -> str:
    rel = path.relative_to(PACKAGE)
    return rel.parts[0] if len(rel.parts) > 1 else rel.stem


def internal_imports(path: Path, tree: ast.AST | None = None) -> list[tuple[str, tuple[str, ...]]]:
    """``(module, names)`` for each import of a ``mobility`` module, module as a dotted path under the package.

    Static imports (``import``, ``from ... import``, relative or absolute) and dynamic ones whose target is
    written out: ``import_module("...")`` with a literal, and the lazy attributes of the package (``_LAZY``).
    ``tree`` (default: the whole module) limits the search to one part of the module.
    """
    tree = ast.parse(path.read_text()) if tree is None else tree
    package_parts = list(path.relative_to(PACKAGE).parts[:-1])

    def relative(level: int, module: str) -> list[str]:
        return package_parts[: len(package_parts) - level + 1] + ([module] if module else [])

    found = []
    for node in ast.walk(tree):
        if isinstance(node, ast.ImportFrom) and node.level:
            base = relative(node.level, "")
            names = tuple(a.name for a in node.names)
            if node.module:
                found.append((".".join(base + [node.module]), names))
            else:  # from . import x: each name is a module or a name of the package
                for name in names:
                    is_module = (PACKAGE.joinpath(*base, name).is_dir() or PACKAGE.joinpath(*base, name + ".py").is_file())
                    found.append((".".join(base + [name]) if is_module else ".".join(base) or "__init__", (name,)))
        elif isinstance(node, ast.ImportFrom) and node.module and node.module.split(".")[0] == "mobility":
            found.append((".".join(node.module.split(".")[1:]) or "__init__", tuple(a.name for a in node.names)))
        elif isinstance(node, ast.Import):
            for alias in node.names:
                if alias.name == "mobility":
                    found.append(("__init__", ()))
                elif alias.name.startswith("mobility."):
                    found.append((alias.name.split(".", 1)[1], ()))
        elif is_dynamic_import(node) and node.args and isinstance(node.args[0], ast.Constant) and isinstance(node.args[0].value, str):
            name = node.args[0].value
            if name.startswith("."):
                found.append((".".join(relative(len(name) - len(name.lstrip(".")), name.lstrip("."))), ()))
            elif name.split(".")[0] == "mobility":
                found.append((".".join(name.split(".")[1:]) or "__init__", ()))
        elif isinstance(node, ast.Assign) and any(isinstance(t, ast.Name) and t.id == "_LAZY" for t in node.targets):
            for key, value in zip(node.value.keys, node.value.values):  # attribute name -> module of the package
                found.append((value.value, (key.value,)))
    return found


def is_dynamic_import(node: ast.AST) -> bool:
    """True for a call of ``import_module`` or ``__import__``, however it was imported."""
    if not isinstance(node, ast.Call):
        return False
    func = node.func
    return (func.attr if isinstance(func, ast.Attribute) else getattr(func, "id", "")) in ("import_module", "__import__")


def is_private(name: str) -> bool:
    return name.startswith("_") and not name.startswith("__")


def private_uses(path: Path, tree: ast.AST | None = None) -> list[str]:
    """The private names of another folder that ``path`` reaches: imported, in a module's path, or as an attribute."""
    folder = folder_of(path)
    tree = ast.parse(path.read_text()) if tree is None else tree
    found = []
    for target, names in internal_imports(path, tree):
        if target.split(".")[0] != folder:
            found += [f"{target}.{n}" for n in names if is_private(n)]
            found += [target for part in target.split(".") if is_private(part)]
    # names bound by an import from another folder (modules or objects), then their private attributes
    foreign = set()
    for node in ast.walk(tree):
        if isinstance(node, (ast.Import, ast.ImportFrom)):
            if any(t.split(".")[0] != folder for t, _ in internal_imports(path, node)):
                foreign |= {alias.asname or alias.name.split(".")[0] for alias in node.names}
    for node in ast.walk(tree):
        if isinstance(node, ast.Attribute) and isinstance(node.value, ast.Name) and node.value.id in foreign and is_private(node.attr):
            found.append(f"{node.value.id}.{node.attr}")
    return found


def dynamic_imports_without_a_literal(path: Path) -> int:
    """How many ``import_module``/``__import__`` calls of ``path`` name their module by a computed string."""
    tree = ast.parse(path.read_text())
    return sum(1 for node in ast.walk(tree) if is_dynamic_import(node) and not (node.args and isinstance(node.args[0], ast.Constant)))


MODULES = sorted(p for p in PACKAGE.rglob("*.py"))
IDS = [str(p.relative_to(PACKAGE)) for p in MODULES]


def allowed(folder: str, target: str) -> bool:
    if target.split(".")[0] == folder:
        return True
    for entry in ALLOWED[folder].split():
        if target == entry or target.startswith(entry + "."):
            return True
    return False


@pytest.mark.parametrize("path", MODULES, ids=IDS)
def test_each_folder_imports_only_what_its_line_allows(path):
    folder = folder_of(path)
    assert folder in ALLOWED, f"{folder}: a folder the architecture does not name; add its line to ALLOWED"
    for target, _ in internal_imports(path):
        assert allowed(folder, target), f"{path.relative_to(PACKAGE)} imports {target}; {folder} may import: {ALLOWED[folder] or 'nothing'}"


@pytest.mark.parametrize("path", [p for p in MODULES if folder_of(p) == "core" and p.stem != "__init__"], ids=lambda p: p.stem)
def test_core_modules_import_lower_layers_only(path):
    name = path.stem
    assert name in CORE_LAYERS, f"core/{name}.py has no layer in CORE_LAYERS"
    for target, _ in internal_imports(path):
        if not target.startswith("core."):
            continue
        other = target.split(".")[1]
        assert other not in CORE_APART.get(name, set()), f"core/{name} imports core/{other}"
        assert CORE_LAYERS[other] < CORE_LAYERS[name], f"core/{name} (layer {CORE_LAYERS[name]}) imports core/{other} (layer {CORE_LAYERS[other]})"


@pytest.mark.parametrize("path", MODULES, ids=IDS)
def test_no_private_name_crosses_a_folder(path):
    assert private_uses(path) == [], f"{path.relative_to(PACKAGE)} reaches private names of another folder"


def test_every_import_by_a_computed_name_stays_in_its_folder():
    # A computed module name cannot be checked against ALLOWED; the one such call loads the CLI's own subcommands.
    computed = {str(p.relative_to(PACKAGE)): n for p in MODULES if (n := dynamic_imports_without_a_literal(p))}
    assert computed == {"__init__.py": 1, "cli/__init__.py": 1}
    # mobility/__init__.py's one: import_module(f".{module}") of a module named in _LAZY (checked above as imports)
    lazy = [t for t, names in internal_imports(PACKAGE / "__init__.py") if names and t.count(".") >= 1]
    assert len(lazy) >= 10 and all(allowed("__init__", t) for t in lazy)
    text = (PACKAGE / "cli" / "__init__.py").read_text()
    assert 'import_module(f"{__name__}.{name}")' in text


def test_every_error_class_lives_in_errors():
    misplaced = []
    for info in pkgutil.walk_packages(mobility.__path__, "mobility."):
        module = importlib.import_module(info.name)
        for name, obj in vars(module).items():
            if inspect.isclass(obj) and issubclass(obj, BaseException) and obj.__module__ == info.name and info.name != "mobility.errors":
                misplaced.append(f"{info.name}.{name}")
    assert misplaced == []


ERROR_BASES = {name for name, obj in vars(mobility.errors).items() if inspect.isclass(obj) and issubclass(obj, BaseException)}


@pytest.mark.parametrize("path", [p for p in MODULES if p.name != "errors.py"], ids=lambda p: str(p.relative_to(PACKAGE)))
def test_no_exception_class_is_defined_anywhere_else_not_even_inside_a_function(path):
    assert exception_classes(ast.parse(path.read_text())) == []


def exception_classes(tree: ast.AST) -> list[str]:
    """The classes defined anywhere in ``tree`` (functions included) whose base is an exception."""

    def base_name(base: ast.expr) -> str:
        return base.attr if isinstance(base, ast.Attribute) else getattr(base, "id", "")

    return [node.name for node in ast.walk(tree) if isinstance(node, ast.ClassDef)
            and any(base_name(b) in ERROR_BASES or base_name(b).endswith(("Error", "Exception", "Warning")) for b in node.bases)]


def test_the_checker_sees_imports():
    # guard against a parser that finds nothing
    found = {t for t, _ in internal_imports(PACKAGE / "core" / "analysis.py")}
    assert {"core.topology", "core.screw_systems", "core.joint_screws", "core.canonical", "core.result"} <= found
    assert "core.analysis" in {t for t, _ in internal_imports(PACKAGE / "cli" / "analyze.py")}
    assert not allowed("io", "core.screws") and allowed("io", "core.model") and not allowed("core", "io.loader")
    assert ("core.finite_screws", ("FiniteScrew", "Limb", "ScrewJoint")) in internal_imports(PACKAGE / "jacobians" / "parallel_model.py")


def test_the_checker_sees_what_a_violation_would_hide_behind():
    core = PACKAGE / "core" / "planted.py"  # a module that is not there: only its place in the package counts
    planted = ast.parse(
        "import importlib\n"
        "import mobility\n"
        "from ..sweeps import runner\n"
        "from ..cli._options import tolerance_from\n"
        "def f():\n"
        "    importlib.import_module('mobility.io.loader')\n"
        "    importlib.import_module('..report.text', __package__)\n"
        "    class Late(ValueError): pass\n"
        "    return runner._private, mobility.io\n"
    )
    targets = {t for t, _ in internal_imports(core, planted)}
    assert {"__init__", "sweeps", "cli._options", "io.loader", "report.text"} <= targets
    assert not any(allowed("core", t) for t in targets - {"core.planted"})
    assert set(private_uses(core, planted)) == {"cli._options", "runner._private"}
    assert exception_classes(planted) == ["Late"]


def test_the_readme_layout_table_states_the_same_lines():
    readme = (PACKAGE.parent / "README.md").read_text(encoding="utf-8")
    section = readme[readme.index("## Layout"):]
    rows = {}
    for line in section.splitlines():
        cells = [c.strip() for c in line.strip().strip("|").split("|")] if line.startswith("| `") else []
        if len(cells) == 3:
            folder = cells[0].strip("`").rstrip("/").removesuffix(".py")
            rows[folder] = cells[2].replace("\\_", "_").replace("nothing", "")
    package_folders = {k: " ".join(v.split()) for k, v in ALLOWED.items() if k not in ("__init__", "__main__")}
    assert {k: " ".join(v.split()) for k, v in rows.items()} == package_folders


LONG_MODULE = 600
"""Lines above which a module must say in its docstring why it is one module (issue 10)."""


def test_a_long_module_says_why_it_reads_better_whole():
    long = {p: len(p.read_text(encoding="utf-8").splitlines()) for p in MODULES}
    long = {p: n for p, n in long.items() if n > LONG_MODULE}
    unexplained = [f"{p.relative_to(PACKAGE)} ({n} lines)" for p, n in long.items()
                   if "longer than most" not in " ".join((ast.get_docstring(ast.parse(p.read_text(encoding="utf-8"))) or "").split())]
    assert long and unexplained == []  # three modules today: core/model, core/kinematics, core/finite_screws
