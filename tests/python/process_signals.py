"""Waiting for a child process to hold a signal, read from /proc/PID/status.

A signal sent before a program catches (SigCgt) or blocks (SigBlk) it ends
the program by its default action; tests that stop a run wait for one of
those states instead of sleeping a fixed time.
"""
import time


def _signal_listed(pid, number, fields):
    # True if one of `fields` ("SigCgt:", "SigBlk:") in /proc/PID/status
    # has the bit of signal `number`; None if the process is gone.
    bit = 1 << (number - 1)
    try:
        with open(f"/proc/{pid}/status") as status:
            return any(line.startswith(fields) and
                       int(line.split()[1], 16) & bit for line in status)
    except FileNotFoundError:
        return None


def wait_until_signal_is_held(process, number, fields=("SigCgt:", "SigBlk:"),
                              timeout=60, required=False):
    """Returns once `process` lists signal `number` in one of `fields`.

    required=False: also returns when the process has ended or at the
    timeout. required=True: asserts that the process is still running and
    raises AssertionError at the timeout.
    """
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        if process.poll() is not None:
            assert not required, "the run ended before it was signalled"
            return
        if _signal_listed(process.pid, number, fields):
            return
        time.sleep(0.002 if not required else 0.05)
    if required:
        raise AssertionError("no handler for signal %d after %d s" %
                             (number, timeout))
