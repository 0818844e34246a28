"""docs/user-model.md's example runs as written on DOLFINx 0.9 (gmshio.model_to_mesh, split_joints,
JointCoupling, NewtonSolver, then SNES), and the two solvers agree with each other."""
import os
import re
import subprocess
import sys

from demo_runner import SOURCE


def _blocks() -> list:
    with open(os.path.join(SOURCE, "docs", "user-model.md"), encoding="utf-8") as f:
        return re.findall(r"```python\n(.*?)```", f.read(), re.S)


def test_user_model_doc_example_runs_with_newton_then_snes(tmp_path):
    example, snes = _blocks()[:2]
    script = tmp_path / "user_model_doc.py"
    script.write_text(example + """
assert converged and iterations >= 2
u_newton = u.x.array.copy()
closure = coupling.state(u)["closure"]
assert (closure > 0).all() and closure.max() < 1e-3                  # closed, below V_m = 1 mm
u.x.array[:] = 0.0                                                     # SNES from rest
""" + snes + """
assert snes.getConvergedReason() > 0
import numpy as np
scale = comm.allreduce(np.abs(u_newton).max(), op=MPI.MAX)
assert comm.allreduce(np.abs(u.x.array - u_newton).max(), op=MPI.MAX) < 1e-8 * scale
""")
    env = dict(os.environ, PYTHONPATH=os.pathsep.join(p for p in sys.path if p), MPLBACKEND="Agg")
    r = subprocess.run([sys.executable, str(script)], cwd=tmp_path, capture_output=True, text=True,
                       env=env, timeout=600)
    assert r.returncode == 0, r.stdout[-3000:] + r.stderr[-3000:]
