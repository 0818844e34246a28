"""The accuracy ladder as data: each law the planner can build from a topography, its closure
error against exact elastic contact (BEM) and its cost per evaluation.

Source: bench/results/accuracy_ladder.md (bench/bench_accuracy_ladder.py, 2026-11-22): synthetic
mated granite-like and sandstone-like joints, 3 seeds x 2 resolutions each, loads 1-30 MPa;
"closure error, mean" (mean over loads, then over joints) and "cost [µs]" (one σ + k evaluation).
Keys are those of rockjoint.laws.laws_from_topography (seated at the measured first contact).
Update these numbers when the ladder is re-run.
"""
from __future__ import annotations

import dataclasses


@dataclasses.dataclass(frozen=True)
class Rung:
    key: str                 # rockjoint.laws.laws_from_topography key
    row: str                 # the row of accuracy_ladder.md
    error_granite: float     # mean closure error, granite-like joints [-]
    error_sandstone: float   # mean closure error, sandstone-like joints [-]
    cost: float              # one σ + k evaluation [s]

    @property
    def error(self) -> float:
        """The error the planner uses: the worse of the two joint families."""
        return max(self.error_granite, self.error_sandstone)


LADDER = (
    Rung("tang_jiao_i2_gw", "Tang & Jiao I2 over GW, seated at first contact **(recommended)**",
         0.073, 0.019, 7.40e-6),
    Rung("greenwood_williamson_empirical", "GW on the measured summits (first contact)",
         0.090, 0.063, 0.25e-6),
    Rung("greenwood_williamson", "GW, seated at first contact", 0.095, 0.050, 2.09e-6),
    Rung("tang_jiao_empirical", "Tang & Jiao I1 over empirical Tang, elastic area",
         0.136, 0.126, 2.63e-6),
    Rung("tang_substrate_empirical", "Tang on the measured summits (first contact)",
         0.136, 0.126, 2.56e-6),
    Rung("tang_substrate", "Tang, seated at first contact", 0.143, 0.117, 7.92e-6),
    Rung("tang_jiao", "Tang & Jiao I1 over Tang, seated at first contact", 0.143, 0.117, 8.06e-6),
)
BY_KEY = {r.key: r for r in LADDER}


def cheapest_within(budget: float):
    """(rung, met): the cheapest law whose error is within `budget`, else the most accurate."""
    fits = [r for r in LADDER if r.error <= budget]
    if fits:
        return min(fits, key=lambda r: r.cost), True
    return min(LADDER, key=lambda r: r.error), False
