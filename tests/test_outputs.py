"""Output files survive failure: an interrupt, a termination or a write error leaves the previous file byte for byte, and no temporary file.

Each case runs the real command line in a child process and does to it what
happens in use: a real ``SIGINT`` or ``SIGTERM`` sent while it writes a big
table, a real write error (a file-size limit, ``RLIMIT_FSIZE``, set in the
child: every write past it fails with ``EFBIG``, as on a full disk).
"""

from __future__ import annotations

import os
import resource
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

import mobility
from mobility.outputs import atomic_output

ROOT = Path(__file__).resolve().parent.parent
FOUR_BAR = str(ROOT / "mechanisms" / "four_bar.yaml")
PREVIOUS = b"the previous output, written by hand\n" * 100
BIG_SWEEP = ["sweep", FOUR_BAR, "--vary", "A=0:6:200000", "--max-poses", "1000000", "--no-progress"]


def _start(*args: str, cwd: Path, preexec_fn=None) -> subprocess.Popen:
    environ = dict(os.environ, PYTHONPATH=str(ROOT))
    return subprocess.Popen([sys.executable, "-m", "mobility", *args], cwd=cwd, env=environ, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                            text=True, preexec_fn=preexec_fn)


def _writing(folder: Path, target: Path) -> bool:
    """Whether the command has started writing ``target``: a temporary file beside it, or (written in place) the target changed."""
    others = [p for p in folder.iterdir() if p != target]
    return bool(others) or target.read_bytes() != PREVIOUS


@pytest.mark.parametrize("signum, status, line", [(signal.SIGINT, 130, "mobility: interrupted\n"), (signal.SIGTERM, 143, "mobility: terminated\n")])
def test_a_signal_while_a_big_table_is_written_leaves_the_previous_file(tmp_path, signum, status, line):
    folder = tmp_path / "out"
    folder.mkdir()
    target = folder / "big.csv"
    target.write_bytes(PREVIOUS)
    child = _start(*BIG_SWEEP, "-o", str(target), cwd=tmp_path)
    deadline = time.monotonic() + 240
    while not _writing(folder, target) and child.poll() is None and time.monotonic() < deadline:
        time.sleep(0.002)
    assert child.poll() is None, child.communicate()  # still running: the signal falls while it writes
    child.send_signal(signum)
    out, err = child.communicate(timeout=60)
    assert (child.returncode, err, out) == (status, line, "")
    assert target.read_bytes() == PREVIOUS  # the old code left 10,001 of 200,001 lines in its place
    assert sorted(p.name for p in folder.iterdir()) == ["big.csv"]  # no temporary file left


def _file_limit(size: int):
    def limit() -> None:
        signal.signal(signal.SIGXFSZ, signal.SIG_IGN)  # a write past the limit fails with EFBIG instead of killing the process
        resource.setrlimit(resource.RLIMIT_FSIZE, (size, size))

    return limit


@pytest.mark.parametrize("command, size", [
    (["sweep", FOUR_BAR, "--vary", "A=0:6:5000", "-o", "{out}/table.csv"], 64 * 1024),
    (["convert", str(ROOT / "mechanisms" / "h4.yaml"), "-o", "{out}/model.yaml"], 1024),
    (["plot", FOUR_BAR, "-o", "{out}/picture.png", "--dpi", "300"], 8 * 1024),
    (["view", FOUR_BAR, "-o", "{out}/page.html"], 64 * 1024),
])
def test_a_write_error_leaves_the_previous_file_and_says_so_in_one_line(tmp_path, command, size):
    folder = tmp_path / "out"
    folder.mkdir()
    args = [a.replace("{out}", str(folder)) for a in command]
    target = Path(args[-1] if args[-2] == "-o" else args[args.index("-o") + 1])
    target.write_bytes(PREVIOUS)
    child = _start(*args, cwd=tmp_path, preexec_fn=_file_limit(size))
    out, err = child.communicate(timeout=120)
    assert child.returncode == 2 and err.count("\n") == 1 and err.startswith("mobility: "), err
    assert "File too large" in err and str(target.name) in err, err
    assert target.read_bytes() == PREVIOUS  # the old code left a fragment in its place
    assert sorted(p.name for p in folder.iterdir()) == [target.name]


def test_an_interrupted_view_leaves_the_old_page_or_a_new_one_with_status_0(tmp_path):
    """Whenever the interrupt falls, a complete new page goes with exit status 0, the old page with 130."""
    folder = tmp_path / "out"
    folder.mkdir()
    target = folder / "page.html"
    outcomes = set()
    for delay in (0.0, 0.5, 1.0, 1.5, 2.0, 2.5, 3.0, 4.0, 6.0):
        target.write_bytes(PREVIOUS)
        child = _start("view", str(ROOT / "mechanisms" / "3prs.yaml"), "--samples", "3", "-o", str(target), cwd=tmp_path)
        start = time.monotonic()
        while time.monotonic() - start < delay and child.poll() is None:
            time.sleep(0.01)
        if child.poll() is None:
            child.send_signal(signal.SIGINT)
        child.communicate(timeout=120)
        page = target.read_bytes()
        assert sorted(p.name for p in folder.iterdir()) == ["page.html"]
        if child.returncode in (130, -signal.SIGINT):  # -SIGINT: interrupted while Python itself was starting, before the command ran
            assert page == PREVIOUS, (delay, child.returncode)
        else:
            assert child.returncode == 0 and page.rstrip().endswith(b"</html>")
        outcomes.add(child.returncode)
    assert 0 in outcomes and outcomes & {130, -signal.SIGINT}  # both were reached: the interrupt fell before and after the page was in place


def test_the_atomic_output_keeps_permissions_follows_links_and_writes_devices_in_place(tmp_path):
    target = tmp_path / "kept.csv"
    target.write_text("old\n")
    target.chmod(0o640)
    link = tmp_path / "link.csv"
    link.symlink_to(target)
    with atomic_output(link) as handle:
        handle.write("new\n")
    assert link.is_symlink() and target.read_text() == "new\n" and (target.stat().st_mode & 0o777) == 0o640
    with atomic_output(os.devnull) as handle:  # not a regular file: written in place, /dev left alone
        handle.write("dropped\n")
    assert os.path.exists(os.devnull) and not os.path.isfile(os.devnull)
    with pytest.raises(ZeroDivisionError):
        with atomic_output(target, binary=True) as handle:
            handle.write(b"partial")
            1 / 0
    assert target.read_text() == "new\n" and sorted(p.name for p in tmp_path.iterdir()) == ["kept.csv", "link.csv"]


def test_an_interrupted_sweep_stops_its_chunks_in_flight_at_once(tmp_path):
    """Chunks of 400,000 poses on two threads: the interrupt used to wait for every chunk in flight (a minute on a busy machine)."""
    child = _start("sweep", str(ROOT / "mechanisms" / "3prs.yaml"), "--vary", "P1=-30:30:200", "--vary", "P2=-30:30:200", "--vary", "P3=-30:30:100",
                   "--max-poses", "10000000", "--no-progress", "--chunk-size", "400000", "--workers", "2", cwd=tmp_path)
    time.sleep(6.0)  # the grid planned, its chunks at work
    assert child.poll() is None
    sent = time.monotonic()
    child.send_signal(signal.SIGINT)
    out, err = child.communicate(timeout=120)
    assert (child.returncode, err, out) == (130, "mobility: interrupted\n", "")
    assert time.monotonic() - sent < 3.0


def test_a_write_error_while_synthesize_writes_its_files_leaves_none_of_them(tmp_path):
    # synthesize --write wrote each file with write_text: a full disk left a fragment, and the files before it
    folder = tmp_path / "pkm"
    folder.mkdir()
    child = _start("synthesize", "2T3R", "--write", str(folder), cwd=tmp_path, preexec_fn=_file_limit(3000))  # some of its files are larger
    out, err = child.communicate(timeout=120)
    assert child.returncode == 2 and err.count("\n") == 1 and "File too large" in err, err
    assert list(folder.iterdir()) == []  # no fragment, no temporary file, and none of the files written before the error
    child = _start("synthesize", "2T3R", "--write", str(folder), cwd=tmp_path)  # without the limit: every file, whole
    out, err = child.communicate(timeout=120)
    assert child.returncode == 0, err
    written = sorted(folder.iterdir())
    assert len(written) >= 7 and all(mobility.load(p).name for p in written)
