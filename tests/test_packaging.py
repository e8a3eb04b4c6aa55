"""The package as it is installed: its name, its version from one place, the library inside it, the install hints.

The distribution is ``mechanism-mobility`` (``mobility`` on the package index is another project); it is imported,
and its command run, as ``mobility``.  The wheel built here by the standard front end (``python -m build``, from
the sdist it builds first) must hold the bundled library; CI also installs that wheel in a fresh virtual
environment and runs the command there (``.ci/run``).
"""

import importlib.metadata
import json
import re
import subprocess
import sys
import tarfile
import tomllib
import zipfile
from pathlib import Path

import pytest

import mobility
from mobility import library
from mobility.cli import main
from mobility.errors import DISTRIBUTION, MissingExtraError, PlottingUnavailableError, RequestError

ROOT = Path(__file__).resolve().parent.parent
PYPROJECT = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))
PROJECT = PYPROJECT["project"]
EXTRAS = set(PROJECT["optional-dependencies"])


def run(capsys, *argv):
    status = main([str(a) for a in argv])
    out, err = capsys.readouterr()
    return status, out, err


# the name and the version


def test_the_distribution_has_a_name_of_its_own_and_the_command_keeps_its_own():
    assert PROJECT["name"] == DISTRIBUTION == "mechanism-mobility"
    assert PROJECT["scripts"] == {"mobility": "mobility.cli:main"}
    assert importlib.metadata.distribution(DISTRIBUTION).read_text("top_level.txt").split() == ["mobility"]


def test_the_version_is_written_in_one_place():
    assert re.fullmatch(r"\d+\.\d+\.\d+", mobility.__version__)
    assert "version" not in PROJECT and PROJECT["dynamic"] == ["version"]
    assert PYPROJECT["tool"]["setuptools"]["dynamic"]["version"] == {"attr": "mobility.__version__"}
    assert importlib.metadata.version(DISTRIBUTION) == mobility.__version__  # what the installed metadata says
    # the changelog's newest released section is this version (below an "Unreleased" one, if any)
    sections = re.findall(r"^## (\S+)", (ROOT / "CHANGELOG.md").read_text(encoding="utf-8"), re.M)
    assert sections[1 if sections[0] == "Unreleased" else 0] == mobility.__version__
    # no other module writes a version of its own
    written = [str(p.relative_to(ROOT)) for p in (ROOT / "mobility").rglob("*.py")
               if re.search(r"^\s*(__version__|VERSION|version)\s*=\s*['\"]\d", p.read_text(encoding="utf-8"), re.M)]
    assert written == ["mobility/__init__.py"]


def test_mobility_version_prints_it(capsys):
    with pytest.raises(SystemExit) as done:
        main(["--version"])
    assert done.value.code == 0 and capsys.readouterr().out == f"mobility {mobility.__version__}\n"
    child = subprocess.run([sys.executable, "-m", "mobility", "--version"], capture_output=True, text=True, timeout=120, cwd=ROOT / "docs")
    assert (child.returncode, child.stdout, child.stderr) == (0, f"mobility {mobility.__version__}\n", "")


# the bundled library


def test_the_library_is_inside_the_package_and_the_clone_paths_name_the_same_files():
    package = Path(mobility.__file__).resolve().parent
    assert library.MECHANISMS == package / "library" / "mechanisms" and library.FLEXURE == package / "library" / "examples" / "flexure"
    clone = sorted(p.stem for p in (ROOT / "mechanisms").glob("*.yaml"))
    assert list(library.names()) == clone and len(clone) == 64
    assert library.flexure_names() == tuple(sorted(p.stem for p in (ROOT / "examples" / "flexure").glob("*.yaml"))) == ("three_rod",)
    for name in library.names():
        assert library.path(name).read_bytes() == (ROOT / "mechanisms" / f"{name}.yaml").read_bytes()
    assert library.path("three_rod").read_bytes() == (ROOT / "examples" / "flexure" / "three_rod.yaml").read_bytes()
    assert library.paths() == tuple(library.path(n) for n in library.names() + library.flexure_names())
    assert not set(library.names()) & set(library.flexure_names())  # a name finds one file


def test_library_path_reads_as_the_loader_expects():
    m = mobility.load(library.path("3prs"))
    assert (m.name, mobility.analyze(m).pattern) == ("3-PRS parallel head (Sprint Z3), symmetric pose", "1T2R")
    assert library.path("3prs.yaml") == library.path("3prs")
    assert mobility.load_flexure(library.path("three_rod")).name == "three-rod spherical flexure (actuation example)"


@pytest.mark.parametrize("name, message", [
    ("benett", "library.path: no file named 'benett' in the bundled library (did you mean 'bennett'?); names: 3crr, 3prs, "),
    ("../mechanisms/3prs", "library.path: no file named '../mechanisms/3prs' in the bundled library"),
    ("", "library.path: no file named '' in the bundled library"),
    (3, "library.path: expected a name (str), got int"),
    (Path("3prs"), "library.path: expected a name (str), got PosixPath"),
])
def test_library_path_refuses_what_is_not_one_of_its_names(name, message):
    with pytest.raises(RequestError) as err:
        library.path(name)
    assert str(err.value).startswith(message) and "\n" not in str(err.value)


def test_import_mobility_reaches_the_library():
    child = subprocess.run([sys.executable, "-c", "import mobility; print(mobility.library.path('bennett').name, len(mobility.library.names()))"],
                           capture_output=True, text=True, timeout=120, cwd=ROOT / "docs")
    assert (child.returncode, child.stdout, child.stderr) == (0, "bennett.yaml 64\n", "")
    assert "library" in mobility.__all__


def test_check_library_checks_every_bundled_file(capsys):
    status, out, err = run(capsys, "check", "--library", "--json")
    report = json.loads(out)
    assert (status, err) == (0, "")
    assert [r["path"] for r in report["results"]] == [str(p) for p in library.paths()]
    assert {r["status"] for r in report["results"]} == {"pass"} and len(report["results"]) == 65
    status, out, _ = run(capsys, "check", "--library")
    assert status == 0 and out.rstrip().endswith("65 passed, 0 failed, 0 without expected block, 0 errors")


def test_check_library_with_paths_of_ones_own_and_without_anything(capsys, write_yaml):
    wrong = write_yaml((ROOT / "mechanisms" / "bennett.yaml").read_text().replace("  dof: 1\n", "  dof: 2\n"), "wrong.yaml")
    status, out, _ = run(capsys, "check", "--library", wrong)
    assert status == 1 and out.rstrip().endswith("65 passed, 1 failed, 0 without expected block, 0 errors")
    assert run(capsys, "check") == (2, "", "mobility: check: give a mechanism file or folder (PATH), or --library for the bundled library\n")


# the install hints


HINT = re.compile(r"pip install(?:\s+(?:--find-links|-f|--constraint|-c|--requirement|-r)\s+\S+|\s+-[-\w]+(?:=\S+)?)*\s+['\"]?([^\s'\"`)]+)")
"""``pip install [options] TARGET``: the first thing installed (an option's argument is not one)."""
EXTRA_OF = re.compile(r"(?<![\w.\-/])(?P<dist>[\w.-]+)\[(?P<extras>[a-z][a-z,]*)\]")
"""``name[extra,...]``, the whole name (``result.mobility[ok]`` is read as ``result.mobility``)."""
CLONE_OR_TOOLS = {".", "pip", "build", "twine", "{DISTRIBUTION}"}
"""What else a ``pip install`` of the repository may install: the clone ('.'), CI's tools, the message's template."""


def text_files():
    """The text of every file of the repository a reader meets (package, tests, docs, README, notebooks, CI)."""
    paths = [ROOT / "README.md", ROOT / "CHANGELOG.md", ROOT / "pyproject.toml", *sorted(p for p in (ROOT / ".ci").iterdir() if p.is_file()), *sorted((ROOT / "docs").glob("*.md")),
             *sorted((ROOT / "notebooks").glob("*.ipynb")), *sorted((ROOT / "mobility").rglob("*.py")),
             *sorted(p for p in (ROOT / "tests").glob("*.py") if p.name != Path(__file__).name)]
    return {str(p.relative_to(ROOT)): p.read_text(encoding="utf-8") for p in paths}


def test_every_install_hint_names_the_distribution_or_the_clone():
    hints = []
    for where, text in text_files().items():
        for found in HINT.finditer(text):
            target = found.group(1)
            hints.append(target)
            # from the index: the distribution (with extras); from a clone: '.' (with extras); CI's tools
            assert target.split("[")[0] in {DISTRIBUTION} | CLONE_OR_TOOLS, f"{where}: pip install {target}"
    assert {f"{DISTRIBUTION}[view]", f"{DISTRIBUTION}[plot]", f"{DISTRIBUTION}[mujoco]", f"{DISTRIBUTION}[dask]", DISTRIBUTION} <= set(hints)


def test_every_extra_named_is_one_of_the_distribution_and_no_text_names_another_package_by_it():
    named = set()
    for where, text in text_files().items():
        for found in EXTRA_OF.finditer(text):
            if found["dist"] in ("mobility", DISTRIBUTION):
                assert found["dist"] == DISTRIBUTION, f"{where}: {found.group(0)} names the other project of the index"
                named |= set(found["extras"].split(","))
    assert named and named <= EXTRAS
    assert {"view", "plot", "mujoco", "dask", "progress"} <= named


def test_the_messages_of_a_missing_extra_name_the_distribution():
    assert str(MissingExtraError("the 3D view", "plotly", "view")).endswith(f": pip install '{DISTRIBUTION}[view]'")
    assert str(PlottingUnavailableError()) == f"plotting needs matplotlib, which is not installed: pip install '{DISTRIBUTION}[plot]'"


# what the standard build front end makes


@pytest.fixture(scope="module")
def built(tmp_path_factory):
    """The sdist and the wheel ``python -m build`` makes (the wheel from the sdist), in a folder of their own."""
    out = tmp_path_factory.mktemp("dist")
    done = subprocess.run([sys.executable, "-m", "build", "--outdir", str(out), str(ROOT)], capture_output=True, text=True, timeout=600)
    assert done.returncode == 0, done.stdout[-2000:] + done.stderr[-2000:]
    (wheel,), (sdist,) = out.glob("*.whl"), out.glob("*.tar.gz")
    return wheel, sdist


def test_the_wheel_holds_the_library_the_version_and_the_command(built):
    wheel, _ = built
    assert wheel.name == f"mechanism_mobility-{mobility.__version__}-py3-none-any.whl"
    with zipfile.ZipFile(wheel) as z:
        package = Path(mobility.__file__).resolve().parent
        for path in library.paths():
            assert z.read(path.relative_to(package.parent).as_posix()) == path.read_bytes()
        assert "mobility/py.typed" in z.namelist()
        info = f"mechanism_mobility-{mobility.__version__}.dist-info"
        metadata = z.read(f"{info}/METADATA").decode()
        assert f"\nName: {DISTRIBUTION}\n" in metadata and f"\nVersion: {mobility.__version__}\n" in metadata
        assert set(re.findall(r"^Provides-Extra: (\S+)$", metadata, re.M)) == EXTRAS
        assert "mobility = mobility.cli:main" in z.read(f"{info}/entry_points.txt").decode()


def test_the_sdist_is_the_whole_source_release(built):
    _, sdist = built
    top = f"mechanism_mobility-{mobility.__version__}"
    with tarfile.open(sdist) as tar:
        names = set(tar.getnames())
        for name in library.names():  # the library in the package, and at the clone's paths (as copies)
            assert f"{top}/mobility/library/mechanisms/{name}.yaml" in names and f"{top}/mechanisms/{name}.yaml" in names
        assert {f"{top}/examples/flexure/three_rod.yaml", f"{top}/CHANGELOG.md", f"{top}/conftest.py", f"{top}/tests/conftest.py",
                f"{top}/tests/test_packaging.py", f"{top}/.ci/run", f"{top}/README.md", f"{top}/pyproject.toml"} <= names
        assert not [n for n in names if "__pycache__" in n or n.endswith(".pyc")]
