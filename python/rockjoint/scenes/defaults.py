"""The planner's numeric defaults, in one place, each with where its value comes from.

Evidence: bench/results/fem.md (DOLFINx 0.9, 2026-11-24) and the demos' own checked settings;
the FE speed-vs-error report (bench/results/fe_speed_vs_error.md) is to replace these citations.
"""
#: P1 elements: every case of bench/results/fem.md runs P1; jointed/intact ratio 1.4-1.7 there.
ELEMENT_DEGREE = 1
#: the nodal joint rule (model default): smooth tractions for stiff joints (docs/fem.md)
QUADRATURE = "nodal"
#: element size on joints / far size: the tunnel and blocky demos refine joints to h/4
JOINT_REFINEMENT = 0.25
#: element size on an opening / far size: the tunnel demo (its Kirsch check, docs/tunnel.md)
OPENING_REFINEMENT = 0.125
#: tables' relative σ and k tolerance: 1e-6, below the Newton tolerance's effect on the closure
#: (bench/results/fem.md: errors vs closed form 1e-11-1e-13 with 1e-6 tables in the column case)
TABLE_TOLERANCE = 1e-6
#: tables of laws over a measured summit list (keys *_empirical): every summit coming into contact
#: is a kink of σ(Δ), which a 1e-6 table cannot follow (TabulatedLaw refuses); 1e-3 is still
#: two orders below the ladder's 6-9 % law errors
TABLE_TOLERANCE_EMPIRICAL = 1e-3
#: the table extends this far past the normal-stress bound (the lab demo: round-off puts points a
#: hair above an exact bound)
TABLE_MARGIN = 1.25
#: load steps for a stage with joints: one step converges in 6 Newton iterations in
#: bench/results/fem.md; stages with strength or excavation take 4 (the tunnel demo's setting)
LOAD_STEPS_ELASTIC = 1
LOAD_STEPS_SLIP = 4
#: stress concentration bound at a circular opening: Kirsch, σ_θ <= 3 σ_1 - σ_3 <= 3 σ_1
OPENING_CONCENTRATION = 3.0
#: stress concentration bound at block corners where joint sets of different orientation cross:
#: the blocky demo's tables go to 2 x the applied stress (its joints reach 1.2 x there)
BLOCK_CORNER_CONCENTRATION = 2.0
#: slip is left out when the mobilised friction ratio τ/τ_max stays below this under the bound
SLIP_MARGIN = 0.5
#: cost figures for words: seconds per 10^5 dofs of a jointed solve, 1 rank
#: (bench/results/fem.md: 5.6 s for 2.0e5 dofs, 3D column, one load step)
SECONDS_PER_DOF = 5.63 / 203118
