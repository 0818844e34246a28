# SPDX-License-Identifier: MIT
"""Run a demo script as a user would (its own process; serially or under mpirun)."""
import os
import subprocess
import sys

SOURCE = os.environ.get("ROCKJOINT_SOURCE_DIR", os.path.join(os.path.dirname(__file__), "..", ".."))


def run_demo(name, out, ranks=1, extra=()):
    """Run demos/<name> with --output <out> on `ranks` processes; fail with its output if it fails.
    Returns the completed process."""
    env = dict(os.environ, PYTHONPATH=os.pathsep.join(p for p in sys.path if p), MPLBACKEND="Agg",
               OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    cmd = [sys.executable, os.path.join(SOURCE, "demos", name), "--output", str(out), *extra]
    if ranks > 1:
        cmd = ["mpirun", "-n", str(ranks)] + cmd
    r = subprocess.run(cmd, capture_output=True, text=True, env=env, timeout=600)
    assert r.returncode == 0, r.stdout + r.stderr
    # A clean run warns about nothing: logging warnings, Python warnings, PETSc's unused options.
    warned = [line for line in (r.stdout + r.stderr).splitlines()
              if "WARNING" in line or "Warning" in line or "warning:" in line]
    assert not warned, f"demos/{name} warned on a clean run:\n" + "\n".join(warned[:20])
    return r
