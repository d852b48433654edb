"""The shared double square and the CLI's --json reports, for the tests
that compare the module with the CLI (test_shellspace.py,
test_cli_parity.py): the mesh paths, reading a mesh, and running a verb of
the built CLI for its report.
"""
import json
import os
import subprocess

import shellspace

DATA = os.environ.get("SHELLSPACE_DATA", "../shared/data")
CLI = os.environ.get("SHELLSPACE_CLI", "build/shellspace")
SQUARE = os.path.join(DATA, "simple", "square4.ply")
SQUARE_BENT = os.path.join(DATA, "simple", "square4_bent.ply")
DOUBLE = os.path.join(DATA, "simple", "double_square.ply")
DOUBLE_BENT = os.path.join(DATA, "simple", "double_square_bent.ply")


def mesh(path):
    return shellspace.read_mesh(path)


# Keys only the CLI's report has: the run's identity (tools/run/run_output.h)
# and the material flag it was given; and its stop state, which the
# Python summaries of the solving functions have too (stop_state=True
# keeps it for them).
CLI_RUN_KEYS = {"run_id", "command_line", "bending_model"}
STOP_STATE_KEYS = {"partial", "stop_reason"}


def cli_json(args, quiet=True, stop_state=False):
    out = subprocess.run([CLI] + args + ["--json"] + ["--quiet"] * quiet,
                         check=True,
                         capture_output=True, text=True).stdout
    report = json.loads(out)
    for key in CLI_RUN_KEYS | (set() if stop_state else STOP_STATE_KEYS):
        report.pop(key, None)
    return report
