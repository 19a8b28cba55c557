"""Output files that never replace what they should not (issue 41, "Output files").

* a character device (``/dev/full``, ``/dev/null``), a FIFO, a directory given as the
  output of any command that writes a file: exit 2 before any work, one line naming the
  option and the path, the node untouched;
* a symbolic link: written through to its target (the link stays a link);
* SIGTERM removes the hidden temporary file as Ctrl-C does (exit 143, one line);
* Ctrl-C while the modules are still importing: ``mstmm: interrupted``, exit 130.

The refusals run the command line in this process with a scene file that does not
exist: the ``--out`` error, not the scene's, shows that the path was checked first.
"""

from __future__ import annotations

import os
import signal
import stat
import subprocess
import sys
import time
from pathlib import Path

import pytest

from mstmm.cli import main

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"
SCENE = str(EXAMPLES / "wu_chou_1998.toml")
FRF = ["--input", "force:x=1.0", "--output", "displacement:x=0.5"]


def _writers(scene: str, out: str) -> list[list[str]]:
    """Every command that writes one file, writing ``out``."""
    return [
        ["frf", scene, *FRF, "--band", "1", "200", "--points", "7", "--out", out],
        ["sweep", scene, "--vary", "beam.EI=1e4,2e4", "--modes", "1", "--out", out],
        ["plot", scene, "-o", out],
        ["solve", scene, "--modes", "2", "--out", out],
        ["bands", scene, "--points", "20", "--out", out],
    ]


def _refused(args: list[str], capsys, *words: str) -> str:
    """Run ``args``: status 2, nothing on standard output, one error line holding ``words``."""
    assert main(args) == 2, args
    captured = capsys.readouterr()
    assert captured.out == "", args
    lines = captured.err.splitlines()
    assert len(lines) == 1 and lines[0].startswith("mstmm: error: <command line>: "), captured
    for word in words:
        assert word in lines[0], (word, lines[0])
    return lines[0]


@pytest.mark.parametrize("device", ["/dev/full", "/dev/null"])
def test_a_character_device_is_refused_before_any_work(device, tmp_path, capsys):
    before = os.stat(device)
    missing = str(tmp_path / "missing.toml")  # the scene would fail, were it read first
    for args in _writers(missing, device):
        if args[0] == "plot":
            continue  # plot checks the suffix first ("/dev/full" has none): exit 2 too
        line = _refused(args, capsys, "--out", "a character device", f"(got '{device}')")
        assert "missing.toml" not in line
    after = os.stat(device)
    assert stat.S_ISCHR(after.st_mode) and after.st_rdev == before.st_rdev


def test_a_fifo_is_refused_and_stays_a_fifo(tmp_path, capsys):
    missing = str(tmp_path / "missing.toml")
    for name in ("fifo.csv", "fifo.png"):
        fifo = tmp_path / name
        os.mkfifo(fifo)
        for args in _writers(missing, str(fifo)):
            if (args[0] == "plot") != name.endswith(".png"):
                continue
            _refused(args, capsys, "--out", "a FIFO", f"(got '{fifo}')")
        assert stat.S_ISFIFO(fifo.lstat().st_mode)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["fifo.csv", "fifo.png"]


def test_an_existing_directory_is_refused_at_the_start(tmp_path, capsys):
    target = tmp_path / "results.png"  # plot wants an image suffix: a directory named so
    target.mkdir()
    missing = str(tmp_path / "missing.toml")
    for args in _writers(missing, str(target)):
        _refused(args, capsys, "--out", "a directory", f"(got '{target}')")
    assert list(target.iterdir()) == []
    assert sorted(p.name for p in tmp_path.iterdir()) == ["results.png"]


def test_a_link_to_a_device_is_refused(tmp_path, capsys):
    link = tmp_path / "out.csv"
    link.symlink_to("/dev/full")
    missing = str(tmp_path / "missing.toml")
    _refused(
        ["frf", missing, *FRF, "--band", "1", "2", "--out", str(link)],
        capsys,
        "a character device (the link leads to /dev/full)",
    )
    assert link.is_symlink() and os.readlink(link) == "/dev/full"


@pytest.mark.parametrize("command", ["frf", "sweep", "solve", "bands", "plot"])
def test_a_symlink_is_written_through_to_its_target(command, tmp_path, capsys):
    """The link stays a link; its target (in another directory) gets the content; no
    temporary file is left beside either."""
    suffix = ".png" if command == "plot" else ".csv"
    (tmp_path / "data").mkdir()
    target = tmp_path / "data" / f"target{suffix}"
    target.write_text("old")
    link = tmp_path / f"link{suffix}"
    link.symlink_to(os.path.relpath(target, tmp_path))
    (args,) = [a for a in _writers(SCENE, str(link)) if a[0] == command]
    assert main(args) in (0, 3), capsys.readouterr().err
    assert link.is_symlink() and link.resolve() == target.resolve()
    content = target.read_bytes()
    assert content != b"old"
    if command == "plot":
        assert content.startswith(b"\x89PNG")
    else:
        assert content.decode().splitlines()[0].split(",")[0] != ""
    assert sorted(p.name for p in tmp_path.rglob("*")) == ["data", link.name, target.name]


def test_a_dangling_symlink_creates_its_target(tmp_path, capsys):
    link = tmp_path / "link.csv"
    link.symlink_to("made.csv")
    args = ["sweep", SCENE, "--vary", "beam.EI=1e4,2e4", "--modes", "1", "--out", str(link)]
    assert main(args) == 0, capsys.readouterr().err
    assert link.is_symlink() and (tmp_path / "made.csv").read_text().count("\n") == 3


def test_derive_out_on_a_device_exits_2(tmp_path, capsys):
    _refused(["derive", str(tmp_path / "missing.toml"), "--out", "/dev/full"], capsys, "--out")


def _default_sigint() -> None:
    # a shell's background job ignores SIGINT and a child inherits that: give the child the
    # default, as a terminal's foreground process has
    signal.signal(signal.SIGINT, signal.SIG_DFL)


def _signal_when(proc, ready, signum: int, settle: float = 0.0, poll: float = 0.05):
    """Send ``proc`` the signal once ``ready()`` holds (and ``settle`` s more, the child
    still running); its standard output and error once it has exited."""
    try:
        deadline = time.monotonic() + 300.0
        while not ready():
            assert proc.poll() is None, proc.communicate()
            assert time.monotonic() < deadline, "not ready in 300 s"
            time.sleep(poll)
        time.sleep(settle)
        assert proc.poll() is None, "the run ended before the signal"
        proc.send_signal(signum)
        return proc.communicate(timeout=120)
    finally:
        proc.kill()


def test_sigterm_removes_the_temporary_file_and_exits_143(tmp_path):
    """``frf --points 5e6 --out``: SIGTERM once the hidden temporary file exists."""
    out = tmp_path / "h.csv"
    proc = subprocess.Popen(
        [sys.executable, "-m", "mstmm", "frf", SCENE, *FRF, "--band", "0", "3000",
         "--points", "5000000", "--out", str(out)],
        stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, cwd=tmp_path,
    )  # fmt: skip
    ready = lambda: bool(list(tmp_path.glob(".tmp-*")))  # noqa: E731
    stdout, stderr = _signal_when(proc, ready, signal.SIGTERM, settle=0.5)  # writing rows
    assert proc.returncode == 143, stderr
    assert stderr == "mstmm: terminated\n" and stdout == ""
    assert list(tmp_path.iterdir()) == []


#: A child that sends itself SIGINT when it first imports ``module``: Ctrl-C while the
#: command line's modules are importing, at a known place.
_CTRL_C_AT_IMPORT = """\
import os, signal, sys
class CtrlC:
    def find_spec(self, name, path=None, target=None):
        if name == {module!r}:
            sys.meta_path.remove(self)
            os.kill(os.getpid(), signal.SIGINT)
        return None
sys.meta_path.insert(0, CtrlC())
{entry}
"""

#: ``python -m mstmm`` and the console script ``mstmm`` (``mstmm.cli:main``).
_ENTRIES = {
    "python -m": "import runpy; sys.argv = ['mstmm', 'solve', '--modes', '2']\n"
    "runpy.run_module('mstmm', run_name='__main__', alter_sys=True)",
    "console script": "from mstmm.cli import main; raise SystemExit(main())",
}


@pytest.mark.parametrize("entry", sorted(_ENTRIES))
@pytest.mark.parametrize("module", ["numpy", "scipy", "numba", "mstmm.scene"])
def test_ctrl_c_while_importing_prints_one_line_and_exits_130(entry, module):
    code = _CTRL_C_AT_IMPORT.format(module=module, entry=_ENTRIES[entry])
    run = subprocess.run(
        [sys.executable, "-c", code, "solve", "--modes", "2"],
        capture_output=True, text=True, timeout=300, preexec_fn=_default_sigint,
    )  # fmt: skip
    assert run.returncode == 130, run.stderr
    assert run.stderr == "mstmm: interrupted\n" and run.stdout == ""


def test_the_package_imports_nothing_heavy():
    """``import mstmm`` and ``import mstmm.cli`` load neither numpy nor numba (what makes
    the Ctrl-C above land inside the command line's handler); the public names still
    resolve, ``mstmm.solve`` and ``mstmm.bands`` as the functions."""
    code = (
        "import sys, mstmm, mstmm.cli\n"
        "assert not {'numpy', 'numba', 'scipy'} & set(sys.modules), sorted(sys.modules)\n"
        "from mstmm import Scene, solve, bands, kernel_for, __version__\n"
        "import mstmm.bands, mstmm.solve, mstmm.output\n"
        "assert mstmm.solve is solve and callable(mstmm.bands) and mstmm.Bands\n"
        "assert all(getattr(mstmm, n) is not None for n in mstmm.__all__)\n"
    )
    run = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert run.returncode == 0, run.stderr


def _mapped(pid: int, library: str) -> bool:
    try:
        with open(f"/proc/{pid}/maps") as fh:
            return library in fh.read()
    except OSError:
        return False


@pytest.mark.skipif(not Path("/proc/self/maps").exists(), reason="needs Linux /proc")
def test_ctrl_c_in_a_fresh_process_as_numpy_loads():
    """``python -m mstmm solve``, SIGINT the moment numpy's C extension is mapped into
    the process (the heavy imports under way; no hook in the child)."""
    proc = subprocess.Popen(
        [sys.executable, "-m", "mstmm", "solve", "--modes", "2"],
        stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, preexec_fn=_default_sigint,
    )  # fmt: skip
    ready = lambda: _mapped(proc.pid, "_multiarray_umath")  # noqa: E731
    stdout, stderr = _signal_when(proc, ready, signal.SIGINT, poll=0.001)
    assert proc.returncode == 130, stderr
    assert stderr == "mstmm: interrupted\n" and stdout == ""


def test_an_interrupt_inside_a_ctypes_callback_is_raised_again_and_not_printed(capfd):
    """numba's machine-code cache is a ctypes callback that LLVM calls while it emits code;
    a Ctrl-C there was "ignored" by ctypes, which printed "Exception ignored on calling
    ctypes callback function" and a traceback (a CI run's ``mstmm solve`` interrupted
    while compiling). Inside ``interrupts_not_lost`` (the whole command line) the
    interrupt comes back in the main thread, SIGINT as KeyboardInterrupt and SIGTERM as
    Terminated, and nothing is printed."""
    import ctypes

    from mstmm.signals import Terminated, interrupts_not_lost, sigterm_as_interrupt

    def raising(exc):
        def callback():
            raise exc

        return ctypes.CFUNCTYPE(None)(callback)

    def spin():  # bytecodes at which the re-armed signal is handled (within a second)
        end = time.monotonic() + 1.0
        while time.monotonic() < end:
            pass

    previous = signal.signal(signal.SIGINT, signal.default_int_handler)
    try:
        sigint = raising(KeyboardInterrupt())
        with pytest.raises(KeyboardInterrupt) as caught:
            with interrupts_not_lost():
                sigint()
                spin()
        assert not isinstance(caught.value, Terminated)
        sigterm = raising(Terminated("SIGTERM"))
        with pytest.raises(Terminated):
            with sigterm_as_interrupt(), interrupts_not_lost():
                sigterm()
                spin()
    finally:
        signal.signal(signal.SIGINT, previous)
    assert capfd.readouterr().err == ""


def test_an_interrupt_that_c_code_turns_into_an_import_error_is_still_an_interrupt():
    """numpy's C extension, interrupted while it imports ``datetime``, raised
    ``ImportError`` (seen once in CI): inside ``interrupts_kept`` (the command line's heavy
    imports) the error is replaced by the interrupt that caused it, SIGINT and SIGTERM."""
    from mstmm.signals import Terminated, interrupts_kept, sigterm_as_interrupt

    def c_code_swallowing(signum: int) -> None:
        try:  # the handler as the signal would run it (os.kill lands at any bytecode: in
            # a gc callback of hypothesis, seen)
            signal.getsignal(signum)(signum, None)
        except KeyboardInterrupt:
            raise ImportError('PyCapsule_Import could not import module "datetime"') from None

    previous = signal.signal(signal.SIGINT, signal.default_int_handler)
    try:
        with pytest.raises(KeyboardInterrupt) as caught:
            with interrupts_kept():
                c_code_swallowing(signal.SIGINT)
        assert not isinstance(caught.value, Terminated)
        with pytest.raises(Terminated):
            with sigterm_as_interrupt(), interrupts_kept():
                c_code_swallowing(signal.SIGTERM)
        with pytest.raises(ImportError):  # no signal: the error is the error
            with interrupts_kept():
                raise ImportError("no module named 'x'")
    finally:
        signal.signal(signal.SIGINT, previous)
