# SPDX-License-Identifier: MIT
"""The weak-scaling model of bench/bench_fem_large.py against the alpha-beta formula by hand.

A run record with round numbers: 2 ranks, 2e6 dofs, 100 Krylov iterations in 10 s, 50 messages,
1 MB and 3 reductions per iteration, a GAMG set-up of 4 s with 1000 messages, 10 MB and 200
reductions, joints 1 s. With intact counts that grow exactly as N^0.25 the fitted exponent must be
0.25; each projected row must equal the formula of projection()'s docstring evaluated here, and
the first row (P = R) must be the run itself (no extra neighbours, log2 2 = 1 reduction stage).
"""
import math
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "..", "bench"))
import bench_fem_large as bench  # noqa: E402


def _event(time=0.0, count=0, messages=0.0, length=0.0, reductions=0.0):
    return {"time": time, "count": count, "numMessages": messages, "messageLength": length,
            "numReductions": reductions}


def _run():
    its = 100
    return {"ranks": 2, "dofs": 2_000_000, "krylov": [20, 30, 50], "interface": 1.0, "events": {
        "KSPSolve": _event(10.0, 3, 50.0 * its, 1e6 * its),
        "PCSetUp": _event(4.0, 1, 1000.0, 1e7, 200.0),
        "VecTDot": _event(count=2 * its), "VecNorm": _event(count=its), "VecDot": _event(), "VecMDot": _event()}}


def test_projection_is_the_alpha_beta_model(monkeypatch):
    monkeypatch.setattr(bench, "MEASURED_ITERATIONS", tuple((n, 40.0 * (n / 1e5) ** 0.25) for n in (1e5, 4e5, 1.6e6)))
    intact = {"dofs": 1_800_000, "krylov": [40.0 * (1.8e6 / 1e5) ** 0.25]}
    alpha, beta, red, nb = 3e-6, 5e9, 4e-6, 13
    rows, gamma = bench.projection(_run(), intact, [64, 1024], alpha, beta, nb, red)
    assert abs(gamma - 0.25) < 1e-12
    assert [r["ranks"] for r in rows] == [2, 64, 1024]
    for r in rows:
        P = r["ranks"]
        scale = 1.0 if P == 2 else nb / 1.0
        its = 100 * (P / 2) ** 0.25
        comm = scale * (50 * alpha + 1e6 / beta) + 3 * red * math.log2(P)
        setup = 4.0 + scale * (1000 * alpha + 1e7 / beta) + 200 * red * math.log2(P)
        expected = setup + its * (0.1 + comm) + 1.0
        assert math.isclose(r["its"], its, rel_tol=1e-12)
        assert math.isclose(r["total"], expected, rel_tol=1e-12), (P, r["total"], expected)
        assert math.isclose(r["efficiency"], rows[0]["total"] / expected, rel_tol=1e-12)
    # the run itself: its compute, setup and joints, plus one log2(2) reduction stage per iteration
    assert math.isclose(rows[0]["total"], 4.0 + 1000 * alpha + 1e7 / beta + 200 * red
                        + 100 * (0.1 + 50 * alpha + 1e6 / beta + 3 * red) + 1.0, rel_tol=1e-12)
