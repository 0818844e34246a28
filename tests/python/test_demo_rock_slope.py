# SPDX-License-Identifier: MIT
"""The rock slope demo (demos/demo_rock_slope.py) runs as it is (--quick, serially), warning-free,
and writes its numbers and pictures; its dry factor of safety is the limit equilibrium of a block
on the cohesionless bedding, tan φ / tan ψ (tan 40° / tan 35°, 3 %), and the water lowers it (with
c = 0 the water in the sliding planes lowers their effective normal stress, hence their friction,
and the water in the crack pushes the block: F wet < F dry)."""
import math
import re

from fe_stack import require_fe  # noqa: E402
require_fe()

import demo_runner  # noqa: E402


def test_the_rock_slope_demo_runs_and_its_dry_factor_is_the_limit_equilibrium(tmp_path):
    demo_runner.run_demo("demo_rock_slope.py", tmp_path, 1, ("--quick",))
    for name in ("rock_slope.txt", "dry/mechanism.png", "wet/mechanism.png", "dry/jointed.xdmf", "wet/summary.txt"):
        assert (tmp_path / name).exists(), name
    text = (tmp_path / "rock_slope.txt").read_text(encoding="utf-8")
    found = {case: float(re.search(rf"^{case}: F = ([0-9.]+)", text, re.M).group(1)) for case in ("dry", "wet")}
    expected = math.tan(math.radians(40.0)) / math.tan(math.radians(35.0))
    assert abs(found["dry"] / expected - 1.0) < 0.03, (found, expected)
    assert found["wet"] < found["dry"]
    assert "intact rock (elastic, no joints): never fails" in text
