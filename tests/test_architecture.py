"""Data flows one way: YAML -> model -> topology -> screw systems -> result -> report/CLI.

The imports of every module are parsed; an arrow pointing backwards fails.
"""

import ast
from pathlib import Path

import pytest

PACKAGE = Path(__file__).resolve().parent.parent / "mobility"

# Layer of each core module: a module may import only modules of its own layer or lower ones.
LAYERS = {
    "errors": 0, "transforms": 0, "tolerance": 0, "expressions": 0, "linalg": 1,
    "yaml_source": 1, "model": 1,
    "loader": 2,
    "screws": 2,
    "topology": 3, "joint_screws": 3,
    "screw_systems": 4, "loop_closure": 4, "canonical": 4,
    "result": 5,
    "analysis": 6,
    "report": 8,
    "cli": 9, "__main__": 9, "__init__": 9,
}
FEATURE_LAYER = 7  # modules built on the analysis (check, finite motion, actuation, plotting, ...)
REPORTING = {"report_markdown": 8, "plotting": 8}

# Separate concerns, whatever the layers say.
FORBIDDEN = {
    "screws": {"loader", "yaml_source", "model", "topology", "joint_screws"},
    "canonical": {"loader", "yaml_source", "model", "topology"},
    "tolerance": {"model", "loader", "screws"},
    "loader": {"screws", "joint_screws", "screw_systems", "canonical", "analysis", "linalg"},
    "model": {"screws", "joint_screws", "topology", "analysis"},
    "topology": {"screws", "joint_screws", "linalg", "tolerance"},
}


def layer(name: str) -> int:
    top = name.split(".")[0]
    return LAYERS.get(top, REPORTING.get(top, FEATURE_LAYER))


def internal_imports(path: Path) -> set[str]:
    tree = ast.parse(path.read_text())
    package_parts = path.relative_to(PACKAGE).parts[:-1]
    found = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.ImportFrom) and node.level:
            base = list(package_parts[: len(package_parts) - node.level + 1])
            target = ".".join(base + ([node.module] if node.module else []))
            if target:
                found.add(target.split(".")[0])
            else:
                found.update(alias.name for alias in node.names)
        elif isinstance(node, ast.ImportFrom) and node.module and node.module.startswith("mobility"):
            parts = node.module.split(".")
            found.add(parts[1] if len(parts) > 1 else "__init__")
        elif isinstance(node, ast.Import):
            for alias in node.names:
                if alias.name.startswith("mobility."):
                    found.add(alias.name.split(".")[1])
    return found


MODULES = sorted(p for p in PACKAGE.rglob("*.py"))


@pytest.mark.parametrize("path", MODULES, ids=[str(p.relative_to(PACKAGE)) for p in MODULES])
def test_imports_point_downstream_only(path):
    rel = path.relative_to(PACKAGE)
    name = rel.parts[0] if len(rel.parts) > 1 else rel.stem
    for target in internal_imports(path):
        assert target not in FORBIDDEN.get(name, set()), f"{rel} imports {target}"
        if name in ("cli", "__main__", "__init__") or target == name:
            continue
        assert target != "cli", f"{rel} imports the command line"
        assert layer(target) <= layer(name), f"{rel} (layer {layer(name)}) imports {target} (layer {layer(target)})"


def test_the_checker_sees_imports():
    # guard against a parser that finds nothing: analysis imports topology and screw systems
    found = internal_imports(PACKAGE / "analysis.py")
    assert {"topology", "screw_systems", "joint_screws", "canonical", "result"} <= found
    assert "analysis" in internal_imports(PACKAGE / "cli" / "analyze.py")
