"""Print the oldest versions pyproject.toml claims, one ``name==version`` a line: pip constraints for CI's third step.

Usage: ``python3 .ci/minimum.py [EXTRA...]``: the core dependencies, and those of each extra named.  Each
requirement ``name>=X`` (``name[extra]>=X``) becomes ``name==X``; a requirement pinned ``==`` stays as it is;
any other form is an error, so that a bound CI cannot test is never declared silently.
"""

import re
import sys
import tomllib
from pathlib import Path

REQUIREMENT = re.compile(r"^(?P<name>[A-Za-z0-9][A-Za-z0-9._-]*)(\[[^\]]*\])?\s*(?P<op>>=|==)\s*(?P<version>[^,;\s]+)$")


def minimum_pins(extras: list[str]) -> list[str]:
    project = tomllib.loads((Path(__file__).resolve().parents[1] / "pyproject.toml").read_text(encoding="utf-8"))["project"]
    optional = project.get("optional-dependencies", {})
    unknown = [e for e in extras if e not in optional]
    if unknown:
        raise SystemExit(f"minimum.py: no extra named {', '.join(unknown)} in pyproject.toml (extras: {', '.join(optional)})")
    pins = {}
    for requirement in [*project["dependencies"], *(r for e in extras for r in optional[e])]:
        found = REQUIREMENT.match(requirement.strip())
        if found is None:
            raise SystemExit(f"minimum.py: {requirement!r}: expected 'name>=version' (or 'name==version') in pyproject.toml")
        pins[found["name"].lower()] = f"{found['name'].lower()}=={found['version']}"
    return sorted(pins.values())


if __name__ == "__main__":
    print("\n".join(minimum_pins(sys.argv[1:])))
