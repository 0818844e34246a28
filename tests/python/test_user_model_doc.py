# SPDX-License-Identifier: MIT
"""docs/user-model.md runs as written: every ```python block of the page, in order, as one script
(the page is written so: each block continues the ones above), on DOLFINx 0.11 as it stands, on
0.9 with the one line the page gives for 0.9 in place of the 0.11 import (and no other change).
A block that fails fails the test; after the page, a few checks that what it computed is what it
says (the joint is nonlinear and closed, the summary is the point state gathered, the strict
table raised with the joint and its range named)."""
import os
import re
import subprocess
import sys

from demo_runner import SOURCE
from rockjoint.fem.compat import DOLFINX_VERSION

IMPORT_011 = "from dolfinx.io import gmsh as gmshio\n"
CHECKS = """
assert problem.solver.getIterationNumber() >= 2                        # the joint is nonlinear
closure = coupling.state(u)["closure"]
assert (closure > 0).all() and closure.max() < 1e-3                    # closed, below V_m = 1 mm
gathered = np.concatenate(comm.allgather(closure))
assert fault.points == gathered.size and fault.max_closure == gathered.max()
assert comm.allgather(fault) == [fault] * comm.size                    # the same on every rank
assert sum(slip.values()) == fault.points and slip["slip"] > 0        # 20° is too little friction for all
assert "joint 'fault'" in message and "its table covers σ_n 0 - 2 MPa" in message, message
print("PAGE-RAN", flush=True)
"""


def page_blocks() -> list:
    with open(os.path.join(SOURCE, "docs", "user-model.md"), encoding="utf-8") as f:
        return re.findall(r"```python\n(.*?)```", f.read(), re.S)


def page_script() -> str:
    """Every block of the page in order, with the 0.9 import on DOLFINx 0.9, then CHECKS."""
    blocks = page_blocks()
    assert len(blocks) >= 5, "the page's example, 0.9 line, strength, range and by-hand blocks"
    example, line_09 = blocks[:2]
    assert example.count(IMPORT_011) == 1 and line_09.startswith("from rockjoint.fem.compat import")
    if DOLFINX_VERSION < (0, 10):
        blocks[0] = example.replace(IMPORT_011, line_09)
        blocks[1] = ""   # the same line, already in place
    return "\n".join(blocks) + CHECKS


def run_page(tmp_path, launcher=()):
    script = tmp_path / "user_model_doc.py"
    script.write_text(page_script())
    env = dict(os.environ, PYTHONPATH=os.pathsep.join(p for p in sys.path if p), MPLBACKEND="Agg")
    return subprocess.run([*launcher, sys.executable, str(script)], cwd=tmp_path, capture_output=True,
                          text=True, env=env, timeout=600)


def test_every_block_of_the_page_runs_in_order(tmp_path):
    r = run_page(tmp_path)
    assert r.returncode == 0 and "PAGE-RAN" in r.stdout, r.stdout[-3000:] + r.stderr[-3000:]
    # a clean run: the strict table raised (caught by the page), nothing warned
    assert "Warning" not in r.stderr and "WARNING" not in r.stdout, r.stderr[-2000:]
    printed = r.stdout.split("PAGE-RAN")[0].strip().splitlines()[-1].split()   # the page's print (gmsh's above)
    assert len(printed) == 3 and int(printed[0]) >= 2 and 0 < float(printed[1]) < 1e-3   # iterations, Δ [m]
