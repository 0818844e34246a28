# SPDX-License-Identifier: MIT
"""A Krylov space carried across Newton steps: deflated preconditioned CG with Ritz vectors of the
earlier solves (an experiment of bench_newton_levers.py; one rank, numpy over the local arrays).

Deflated PCG (Saad, Yeung, Erhel & Guyomarc'h 2000, SIAM J. Sci. Comput. 21, Alg. 3.6): with a
basis W and E = Wᵀ A W the start x0 = W E⁻¹ Wᵀ b makes Wᵀ r0 = 0, and every search direction is
z - W E⁻¹ (AW)ᵀ z, so the iteration never re-enters span W. W collects, after every solve, the
Ritz vectors of its `ritz` smallest Ritz values: the Lanczos tridiagonal of preconditioned CG,
T_jj = 1/α_j + β_{j-1}/α_{j-1}, T_j,j+1 = √β_j / α_j, on the Lanczos vectors z_j / √(r_j·z_j)
(Saad, Iterative Methods, §6.7.3), the oldest dropped beyond `keep` columns. The preconditioner is
the model's lagged GAMG (built at the first solve, reused as the project's solver reuses it).
"""
from __future__ import annotations

import numpy as np


def use_deflated_cg(model, keep: int, ritz: int) -> None:
    """Replace the model's linear solve by deflated PCG with up to `keep` Ritz vectors (`ritz` new
    ones per solve); 0, 0: plain PCG with the same lagged preconditioner (the reference)."""
    ls = model.linear_solver
    state = {"W": None, "built": False}

    def solve(A, b, x, rtol=None):
        rtol = ls.rtol if rtol is None else max(rtol, ls.rtol)
        pc = ls.ksp.getPC()
        if not state["built"]:
            ls.ksp.setOperators(A)
            ls.flag(A)   # the near-nullspace
            pc.setReusePreconditioner(False)
            pc.setUp()
            pc.setReusePreconditioner(True)   # PCApply would rebuild it for every new Jacobian
            ls.setups += 1
            state["built"] = True
        vin, vout = b.duplicate(), b.duplicate()

        def apply(op, v):
            vin.array[:] = v
            op(vin, vout)
            return vout.array.copy()
        its = _pcg(lambda v: apply(A.mult, v), lambda v: apply(pc.apply, v), b.array.copy(), rtol, state, ritz, keep)
        x.array[:] = state.pop("x")
        ls.iterations.append(its)
        return its

    ls.solve = solve


def _pcg(A, M, b, rtol, state, ritz, keep) -> int:
    W = state["W"]
    x = np.zeros_like(b)
    if W is not None:
        AW = np.column_stack([A(w) for w in W.T])
        Einv = np.linalg.pinv(W.T @ AW, rcond=1e-12)
        x = W @ (Einv @ (W.T @ b))
        r = b - A(x)
    else:
        r = b.copy()

    def project(z):
        return z if W is None else z - W @ (Einv @ (AW.T @ z))
    z = M(r)
    p, rz = project(z), r @ z
    alphas, betas, lanczos = [], [], []
    bn = np.linalg.norm(b)
    while np.linalg.norm(r) > rtol * bn and len(alphas) < 2000:
        lanczos.append(z / np.sqrt(rz))
        Ap = A(p)
        a = rz / (p @ Ap)
        x += a * p
        r -= a * Ap
        z = M(r)
        rz_new = r @ z
        alphas.append(a)
        betas.append(rz_new / rz)
        p, rz = project(z) + betas[-1] * p, rz_new
    state["x"] = x
    m = len(alphas)
    if ritz > 0 and m >= 2:
        T = np.diag([1.0 / alphas[j] + (betas[j - 1] / alphas[j - 1] if j else 0.0) for j in range(m)])
        off = [np.sqrt(betas[j]) / alphas[j] for j in range(m - 1)]
        T += np.diag(off, 1) + np.diag(off, -1)
        _, S = np.linalg.eigh(T)
        Y = np.column_stack(lanczos) @ S[:, :ritz]
        W = Y if W is None else np.column_stack([W, Y])[:, -keep:]
        Q, R = np.linalg.qr(W)
        state["W"] = Q[:, np.abs(np.diag(R)) > 1e-10 * np.abs(R).max()]
    return m
