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
    "core": "errors",
    "io": "errors core.model core.transforms core.tolerance",
    "finite": "errors core",
    "actuation": "errors core",
    "flexure": "errors core io actuation",
    "synthesis": "errors core io",
    "jacobians": "errors core",
    "sweeps": "errors core actuation",
    "report": "errors core finite actuation flexure synthesis jacobians sweeps testing",
    "view": "errors core report sweeps",
    "testing": "errors core io finite",
    "cli": "__init__ errors core io finite actuation flexure synthesis jacobians sweeps report view testing",
    "__init__": "errors core io finite actuation flexure synthesis jacobians sweeps report view testing",
    "__main__": "cli",
}

# Inside the core, data flows by layer: a module imports only modules of lower layers.
CORE_LAYERS = {
    "tolerance": 0, "transforms": 0,
    "linalg": 1, "model": 1, "finite_screws": 1,
    "screws": 2, "topology": 2,
    "joint_screws": 3,
    "screw_systems": 4, "loop_closure": 4, "canonical": 4, "kinematics": 4,
    "result": 5, "poses": 5,
    "analysis": 6,
}
# ... and screw algebra knows no model, the topology no geometry.
CORE_APART = {
    "screws": {"model", "topology", "joint_screws"},
    "canonical": {"model", "topology", "joint_screws"},
}


def folder_of(path: Path) -> str:
    rel = path.relative_to(PACKAGE)
    return rel.parts[0] if len(rel.parts) > 1 else rel.stem


def internal_imports(path: Path) -> list[tuple[str, tuple[str, ...]]]:
    """``(module, names)`` for each import of a ``mobility`` module, module as a dotted path under the package."""
    tree = ast.parse(path.read_text())
    package_parts = list(path.relative_to(PACKAGE).parts[:-1])
    found = []
    for node in ast.walk(tree):
        if isinstance(node, ast.ImportFrom) and node.level:
            base = package_parts[: len(package_parts) - node.level + 1]
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
                if alias.name.startswith("mobility."):
                    found.append((alias.name.split(".", 1)[1], ()))
    return found


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
    folder = folder_of(path)
    for target, names in internal_imports(path):
        if target.split(".")[0] == folder:
            continue
        private = [n for n in names if n.startswith("_") and not n.startswith("__")]
        assert not private, f"{path.relative_to(PACKAGE)} imports private {private} from {target}"


def test_every_error_class_lives_in_errors():
    misplaced = []
    for info in pkgutil.walk_packages(mobility.__path__, "mobility."):
        module = importlib.import_module(info.name)
        for name, obj in vars(module).items():
            if inspect.isclass(obj) and issubclass(obj, BaseException) and obj.__module__ == info.name and info.name != "mobility.errors":
                misplaced.append(f"{info.name}.{name}")
    assert misplaced == []


def test_the_checker_sees_imports():
    # guard against a parser that finds nothing
    found = {t for t, _ in internal_imports(PACKAGE / "core" / "analysis.py")}
    assert {"core.topology", "core.screw_systems", "core.joint_screws", "core.canonical", "core.result"} <= found
    assert "core.analysis" in {t for t, _ in internal_imports(PACKAGE / "cli" / "analyze.py")}
    assert not allowed("io", "core.screws") and allowed("io", "core.model") and not allowed("core", "io.loader")
    assert ("core.finite_screws", ("FiniteScrew", "Limb", "ScrewJoint")) in internal_imports(PACKAGE / "jacobians" / "jacobian.py")
