# SPDX-License-Identifier: MIT
"""The planner's numeric defaults, in one place, each with where its value comes from.

Evidence: the FE speed-vs-error report (bench/results/fe_speed_vs_error.md, DOLFINx 0.9) for the
mesh, element, joint rule, table tolerance and load steps; the demos' own checked settings and the
closed forms cited below for the rest.
"""
import dataclasses
import math


@dataclasses.dataclass(frozen=True)
class FESettings:
    """FE settings that meet an error budget on the report's jointed tunnels (P2 fine reference)."""
    error_budget: float                 #: max(wall error, joints' share error) the row is chosen for
    element_degree: int
    quadrature: str                     #: joint rule
    opening_size_over_radius: float     #: element size on an opening / its radius
    joint_size_over_spacing: float      #: element size on joints / the smallest joint spacing
    far_size_over_radius: float         #: the report's far size / radius (the scene's size rules)
    table_tolerance: float              #: relative σ, k tolerance of the joints' tables
    load_steps: int                     #: load steps of a stage with elastic joints
    measured_error: float               #: the answer error the row got (benchmark tunnel)
    measured_error_second_scene: float  #: the same ratios on the second scene (bedding 1.5 m, K0 1.5)


#: FE settings by error budget, loosest first: the report's recommended rows (bench/results/
#: fe_speed_vs_error.md §8, JSON "by_budget", produced by bench/bench_fe_speed_vs_error.py; the
#: test tests/python/test_scenes_fe_settings.py keeps these equal to that JSON). Tighter budgets
#: than the last row were not met by any mesh of the sweep on both scenes: the planner then uses
#: the last row and says that its error is not demonstrated.
FE_SETTINGS = (
    FESettings(0.1, 1, "nodal", 0.125, 1.0 / 3.0, 1.0, 0.01, 1, 0.0477, 0.0889),
    FESettings(0.03, 1, "nodal", 0.03125, 1.0 / 12.0, 0.25, 0.01, 1, 0.00678, 0.0273),
)


def fe_settings(budget: float) -> tuple:
    """(settings, met): the loosest FE_SETTINGS row whose budget is within `budget`; met = False
    (and the tightest row) when the report met no row that tight."""
    rows = [s for s in FE_SETTINGS if s.error_budget <= budget]
    if rows:
        return max(rows, key=lambda s: s.error_budget), True
    return min(FE_SETTINGS, key=lambda s: s.error_budget), False


#: the table extends this far past the normal-stress bound (the lab demo: round-off puts points a
#: hair above an exact bound)
TABLE_MARGIN = 1.25
#: load steps for a stage with slip: path dependent; the tunnel demo's setting (4 excavation steps)
LOAD_STEPS_SLIP = 4
#: stress concentration bound at a circular opening: Kirsch, σ_θ <= 3 σ_1 - σ_3 <= 3 σ_1
OPENING_CONCENTRATION = 3.0
#: stress concentration bound at block corners where joint sets of different orientation cross:
#: the blocky demo's tables go to 2 x the applied stress (its joints reach 1.2 x there)
BLOCK_CORNER_CONCENTRATION = 2.0
#: slip is left out when the mobilised friction ratio τ/τ_max stays below this under the bound
SLIP_MARGIN = 0.5
#: cost figures for words: seconds per dof of a jointed 2D solve, 1 rank, P1 (bench/results/
#: fe_speed_vs_error.md §3: 26926 dofs in 0.71 s, n = 32, in-situ + excavation, a loaded machine)
SECONDS_PER_DOF = 0.71 / 26926

#: Discrete against smeared joint sets (equivalent continuum, docs/equivalent-continuum.md): the
#: tunnel rows of bench/results/continuum.md (bench/bench_continuum.py, 2026-11-29 00:23 UTC; a = 4 m,
#: two Coulomb sets, spacings s and 2 s), as (s/a, error of the all-smeared model, its speed-up over
#: the discrete one, error of the mixed model (dominant set discrete, the rest smeared), its
#: speed-up). Error: the larger of the crown and sidewall convergence gaps to the discrete model,
#: at s/a = 0.0625 the largest over the bench's mesh check (far-field meshes of 1.5, 1.0, 0.75 m:
#: all smeared, sidewall -42, -34, -30 %; mixed, sidewall -7.7, -3.8, -3.0 %); inf would mark a
#: model that failed. Speed-ups: the fastest of 2 runs of each model. Kept equal to the report by
#: tests/python/test_docs_match_results.py.
#: The planner (smearing.smeared_sets) smears a set where the row at the nearest ratio at or above
#: its own is within the budget and faster.
SMEARED_EVIDENCE = ((1.0, 0.728, 0.1, 0.176, 0.6), (0.5, 0.769, 0.1, 0.289, 0.8),
                    (0.25, 0.133, 0.1, 0.089, 1.0), (0.125, 0.083, 0.4, 0.206, 1.5),
                    (0.0625, 0.420, 1.1, 0.077, 2.4))

#: Two-way water (docs/flow.md): staggered iterations of the coupled steady state with
#: coupled_steady's defaults (the network step with the joints' local response, IQN-ILS), the
#: larger of the measured counts: 3 on the verification column, 2D and 3D
#: (bench/results/coupled_water.md) and 4 on the tunnel drained below a water table
#: (bench/results/coupled_water_tunnel.md), 2026-11-29; each iteration is one mechanical stage
#: solve and one network solve
COUPLED_ITERATIONS = 4
