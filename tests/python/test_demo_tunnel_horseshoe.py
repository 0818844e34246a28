# SPDX-License-Identifier: MIT
"""Issue 40: the tunnel demo's section as a horseshoe (demos/demo_tunnel.py --opening horseshoe
--quick: demos/scenes/tunnel_horseshoe.yaml at its reduced size) runs as it is, warning-free, and
writes its pictures, XDMF and summary; the summary's intact opening converges and the joints add to
it (jointed minus intact > 0: the joints add compliance)."""
import re

from fe_stack import require_fe  # noqa: E402
require_fe()

import demo_runner  # noqa: E402


def test_horseshoe_tunnel_demo_runs_clean(tmp_path):
    r = demo_runner.run_demo("demo_tunnel.py", tmp_path, 1, ("--quick", "--opening", "horseshoe"))
    out = tmp_path / "tunnel_horseshoe"
    for name in ("summary.txt", "scene.png", "jointed.xdmf", "intact.xdmf", "jointed_joints.xdmf"):
        assert (out / name).exists(), name
    assert not (tmp_path / "tunnel.txt").exists()   # the circular demo did not run
    row = re.search(r"^excavation\s+mean u_n opening \[mm\]\s+(\S+)\s+(\S+)\s+(\S+)$",
                    (out / "summary.txt").read_text(), re.M)
    assert row, r.stdout
    jointed, intact, share = (float(v) for v in row.groups())
    assert intact > 0.0 and share > 0.0 and jointed > intact
