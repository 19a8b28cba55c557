"""Ctrl-C a command line in a child process: :func:`interrupt` (for any long command)."""

from __future__ import annotations

import signal
import subprocess
import sys
import time


def interrupt(args: list[str], wait: float) -> tuple[int, str, str, float]:
    """Run ``mstmm.cli.main(args)`` in a child, send it SIGINT ``wait`` s after it
    started, and return its status, standard output, standard error and the seconds it
    took to exit after the signal. The child must still be running when the signal comes."""
    code = (
        "import sys\n"
        "from mstmm.cli import main\n"
        "sys.stderr.write('ready\\n'); sys.stderr.flush()\n"
        f"raise SystemExit(main({args!r}))\n"
    )
    # a shell's background job ignores SIGINT, and a child inherits that (Python then keeps
    # no handler): give the child the default, as a terminal's foreground process has
    proc = subprocess.Popen(
        [sys.executable, "-c", code],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL),
    )
    try:
        assert proc.stderr.readline() == "ready\n"
        time.sleep(wait)
        assert proc.poll() is None, f"{args[0]} ended before it could be interrupted"
        t0 = time.perf_counter()
        proc.send_signal(signal.SIGINT)
        out, err = proc.communicate(timeout=120)
        took = time.perf_counter() - t0
    finally:
        proc.kill()
    return proc.returncode, out, err, took
