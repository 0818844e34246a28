# SPDX-License-Identifier: MIT
"""The cases and the selection rule of bench/bench_fe_speed_vs_error.py, at coarse sizes (serial).

- Column: its exact solution (uniform stress, a constant jump per joint) lies in the P1 space, so
  P1 nodal, P1 Gauss and P2 all meet the closed form to solver tolerance (1e-8) on a coarse mesh.
- Table tolerance: for Barton-Bandis σ/(k Δ) = 1 - Δ/V_m < 1, so a relative σ error ε of the
  table gives a relative closure error below ε and a relative top-displacement error below ε: the
  column's FE error with a table must stay under the table's tolerance.
- Jointed tunnel against a P2 reference two refinements finer: the wall error falls from n = 4 to
  n = 8 (P1) and P2 beats P1 on the same mesh.
- recommend(): the cheapest nodal row meeting the budget, on a hand-made results table.
"""
import os
import sys

import pytest

from fe_stack import require_fe  # noqa: E402
require_fe()

from mpi4py import MPI  # noqa: E402

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "..", "bench"))
import bench_fe_speed_vs_error as bench  # noqa: E402

COMM = MPI.COMM_SELF


@pytest.fixture(scope="module")
def column_mesh():
    return bench.column_mesh(0.25, COMM)


@pytest.mark.parametrize("degree, quadrature", [(1, "nodal"), (1, "gauss"), (2, "nodal")])
def test_column_meets_the_closed_form_at_any_mesh(column_mesh, degree, quadrature):
    row = bench.solve_column(column_mesh, element_degree=degree, quadrature=quadrature)
    assert row["error"] < 1e-8, row


def test_a_table_adds_less_than_its_tolerance_to_the_column(column_mesh):
    import rockjoint
    law = rockjoint.BartonBandis(bench.bench_fem.KNI, bench.bench_fem.VM)
    for tol in (1e-2, 1e-4):
        table = rockjoint.tabulate(law, max_stress=2 * bench.bench_fem.COLUMN_STRESS, tolerance=tol)
        row = bench.solve_column(column_mesh, law=table)
        assert row["error"] < tol, (tol, row)


def test_jointed_tunnel_error_falls_with_h_and_with_p2():
    ref = bench.solve_tunnel(bench.tunnel_mesh(16, COMM), degree=2)
    coarse, fine = bench.tunnel_mesh(4, COMM), bench.tunnel_mesh(8, COMM)
    p1_4 = bench.tunnel_errors(bench.solve_tunnel(coarse), ref)
    p1_8 = bench.tunnel_errors(bench.solve_tunnel(fine), ref)
    p2_8 = bench.tunnel_errors(bench.solve_tunnel(fine, degree=2), ref)
    assert p1_8["wall_error"] < 0.7 * p1_4["wall_error"], (p1_4, p1_8)
    assert p2_8["wall_error"] < 0.5 * p1_8["wall_error"], (p1_8, p2_8)


def test_recommend_picks_the_cheapest_row_meeting_the_budget():
    def row(n, degree, quadrature, err, seconds):
        return {"n": n, "degree": degree, "quadrature": quadrature, "wall_error": err, "stress_error": err,
                "seconds": seconds, "dofs": 100 * n}
    res = {
        "tunnel": {"mesh": [row(8, 1, "nodal", 0.025, 1.0), row(8, 1, "gauss", 0.01, 1.0), row(16, 1, "nodal", 0.008, 3.0),
                            row(16, 1, "gauss", 0.007, 3.0), row(8, 2, "nodal", 0.004, 2.0)],
                   "table_tolerance": [{"tolerance": 1e-2, "wall_error": 2e-3}, {"tolerance": 1e-4, "wall_error": 1e-5},
                                       {"tolerance": None, "wall_error": 0.0}],
                   "load_steps": [{"steps": 1, "newton_iterations": 7, "seconds": 1.0},
                                  {"steps": 2, "newton_iterations": 9, "seconds": 1.1}]},
        "column": {"table_tolerance": [{"tolerance": 1e-2, "error": 1e-6}, {"tolerance": 1e-4, "error": 1e-8}]},
        "kirsch": {"rows": [{"degree": 2, "a/h": 4, "displacement_max": 0.02}, {"degree": 2, "a/h": 8,
                                                                                 "displacement_max": 0.003}]},
    }
    rec = bench.recommend(res, 0.01)
    assert rec["element_degree"] == 2 and rec["mesh_family_n"] == 8       # 2.0 s beats P1 n = 16 (3.0 s)
    assert rec["table_tolerance"] == 1e-4                                 # 1e-2 costs 2e-3 > budget / 10
    assert rec["excavation_load_steps"] == 1
    assert rec["intact_opening_mesh_size_over_radius"] == pytest.approx(1 / 8)
    rec = bench.recommend(res, 0.03)
    assert rec["element_degree"] == 1 and rec["mesh_family_n"] == 8 and rec["joint_quadrature"] == "gauss"
    assert not bench.recommend(res, 1e-3)["met"]
