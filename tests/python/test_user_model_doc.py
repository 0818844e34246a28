"""docs/user-model.md's example runs as written: on DOLFINx 0.11 as it stands, on 0.9 with the one
line the page gives for 0.9 in place of the 0.11 import (and no other change)."""
import os
import re
import subprocess
import sys

from demo_runner import SOURCE
from rockjoint.fem_coupling.compat import DOLFINX_VERSION

IMPORT_011 = "from dolfinx.io import gmsh as gmshio\n"


def _blocks() -> list:
    with open(os.path.join(SOURCE, "docs", "user-model.md"), encoding="utf-8") as f:
        return re.findall(r"```python\n(.*?)```", f.read(), re.S)


def test_user_model_doc_example_runs_as_written(tmp_path):
    example, line_09 = _blocks()[:2]
    assert example.count(IMPORT_011) == 1
    if DOLFINX_VERSION < (0, 10):
        example = example.replace(IMPORT_011, line_09)
    script = tmp_path / "user_model_doc.py"
    script.write_text(example + """
assert problem.solver.getIterationNumber() >= 2                        # the joint is nonlinear
closure = coupling.state(u)["closure"]
assert (closure > 0).all() and closure.max() < 1e-3                    # closed, below V_m = 1 mm
""")
    env = dict(os.environ, PYTHONPATH=os.pathsep.join(p for p in sys.path if p), MPLBACKEND="Agg")
    r = subprocess.run([sys.executable, str(script)], cwd=tmp_path, capture_output=True, text=True,
                       env=env, timeout=600)
    assert r.returncode == 0, r.stdout[-3000:] + r.stderr[-3000:]
    assert "Warning" not in r.stderr and "WARNING" not in r.stdout, r.stderr[-2000:]
