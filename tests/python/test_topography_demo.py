# SPDX-License-Identifier: MIT
"""The topography demo runs as it is and prints its parameter table (theory §7 ranges)."""
import os
import re
import subprocess
import sys

DEMO = os.path.join(os.environ.get("ROCKJOINT_SOURCE_DIR",
                                   os.path.join(os.path.dirname(__file__), "..", "..")),
                    "demos", "demo_topography_to_closure.py")


def test_demo_topography_to_closure_runs(tmp_path):
    env = dict(os.environ, PYTHONPATH=os.pathsep.join(p for p in sys.path if p),
               MPLBACKEND="Agg")
    r = subprocess.run([sys.executable, DEMO, "--output", str(tmp_path)], capture_output=True,
                       text=True, env=env, timeout=300)
    assert r.returncode == 0, r.stderr
    assert (tmp_path / "closure_curves.png").exists()
    # Parameter table rows: name, η [1/mm²], β [mm], σ_s [mm] | spectral ...
    for name in ("granite-like", "sandstone-like"):
        m = re.search(rf"^{name}\s+([\d.]+)\s+([\d.]+)\s+([\d.]+) \|", r.stdout, re.M)
        assert m, r.stdout
        eta, beta, sigma = map(float, m.groups())
        # theory §7: η ≈ 0.05-0.4 /mm², β ≈ 1-10 mm, σ_s ≈ 0.01-0.1 mm at 0.5 mm sampling
        assert 0.05 <= eta <= 0.4 and 1 <= beta <= 10 and 0.01 <= sigma <= 0.1, m.group(0)
