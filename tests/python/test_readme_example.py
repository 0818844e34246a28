# SPDX-License-Identifier: MIT
"""The README's Python walkthrough runs as written (topography → law → table → staged tunnel)."""
import os
import subprocess
import sys

from demo_runner import SOURCE


def _readme_block() -> str:
    with open(os.path.join(SOURCE, "README.md"), encoding="utf-8") as f:
        text = f.read()
    section = text.split("## The pipeline in Python", 1)[1]
    return section.split("```python", 1)[1].split("```", 1)[0]


def test_readme_python_walkthrough_runs(tmp_path):
    script = tmp_path / "readme_walkthrough.py"
    # The walkthrough's own statements, then checks that each stage produced what it says.
    script.write_text(_readme_block() + """
assert set(laws) >= {"greenwood_williamson", "tang_jiao"}, sorted(laws)
assert abs(closure - 0.125e-3) < 0.01e-3, closure          # the README's "≈ 0.125 mm"
assert os.path.exists("granite.rjt")
stages = [s.name for s in model.stages]
assert stages == ["in-situ", "excavation"], stages
closure_change = excavated.gather_joints()["closure"]
assert closure_change.size > 0 and (closure_change > 0).all()   # bedding stays closed under σ0
""")
    env = dict(os.environ, PYTHONPATH=os.pathsep.join(p for p in sys.path if p), MPLBACKEND="Agg")
    r = subprocess.run([sys.executable, "-c", "import os\nexec(open('readme_walkthrough.py').read())"],
                       cwd=tmp_path, capture_output=True, text=True, env=env, timeout=600)
    assert r.returncode == 0, r.stdout[-3000:] + r.stderr[-3000:]
