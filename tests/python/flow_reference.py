# SPDX-License-Identifier: MIT
"""An independent finite-volume solve of the Reynolds (local cubic law) equation, for the flow
tests: the same discretisation as flow/reynolds_flow.hpp (cells, harmonic-mean faces, unit mean
gradient), written again with numpy and SciPy (SuperLU with partial pivoting, not a Cholesky),
with no region analysis: every connected group of open cells is solved, and groups that do not
carry a mean flow come out with no flux by themselves."""
import numpy as np
import scipy.sparse as sp
import scipy.sparse.csgraph as csgraph
import scipy.sparse.linalg as spla


def _faces(k, axis, periodic):
    """(cell, neighbour, conductance) of every face normal to `axis` (0: x, the columns)."""
    rows, cols = k.shape
    idx = np.arange(rows * cols).reshape(rows, cols)
    a, b, ka, kb = idx, np.roll(idx, -1, axis=1 - axis), k, np.roll(k, -1, axis=1 - axis)
    if not periodic:   # drop the wrapped faces
        keep = (slice(None), slice(0, cols - 1)) if axis == 0 else (slice(0, rows - 1), slice(None))
        a, b, ka, kb = a[keep], b[keep], ka[keep], kb[keep]
    with np.errstate(invalid="ignore", divide="ignore"):
        c = np.where((ka > 0) & (kb > 0), 2 * ka * kb / (ka + kb), 0.0)
    return a.ravel(), b.ravel(), c.ravel()


def transmissivity(e, h, periodic):
    """(T_xx, T_yy) [m³] of aperture field e [m] (rows = y, cols = x; 0 = closed) on a square grid
    of spacing h: mean flux per unit width under a unit mean pressure gradient."""
    e = np.asarray(e, dtype=float)
    rows, cols = e.shape
    n = rows * cols
    k = np.where(e > 0, e ** 3 / 12, 0.0)
    out = []
    for axis in (0, 1):
        faces = [_faces(k, ax, periodic) for ax in (0, 1)]
        a = np.concatenate([f[0] for f in faces])
        b = np.concatenate([f[1] for f in faces])
        c = np.concatenate([f[2] for f in faces])
        a, b, c = a[c > 0], b[c > 0], c[c > 0]
        lap = sp.coo_matrix((np.concatenate([-c, -c, c, c]),
                             (np.concatenate([a, b, a, b]), np.concatenate([b, a, a, b]))),
                            shape=(n, n)).tocsr()
        rhs = np.zeros(n)
        length = (cols if axis == 0 else rows) * h
        pos = np.arange(n)
        line = pos % cols if axis == 0 else pos // cols
        if periodic:
            # p = -x_axis + φ: a face crossing the axis carries c (φ_a - φ_b + h); one cell of each
            # connected group pinned (φ is defined up to a constant there)
            na, nb, nc = faces[axis]
            np.add.at(rhs, na, -nc * h)
            np.add.at(rhs, nb, nc * h)
            _, group = csgraph.connected_components(lap != 0, directed=False)
            pinned = np.zeros(n, bool)
            for g in np.unique(group[k.ravel() > 0]):
                members = np.flatnonzero(group == g)
                pinned[members[np.argmax(k.ravel()[members])]] = True
        else:
            inlet, outlet = line == 0, line == (cols if axis == 0 else rows) - 1
            boundary = 2 * k.ravel()   # half cell to the face: conductance 2k over h, times h
            diag = np.where(inlet | outlet, boundary, 0.0)
            lap = lap + sp.diags(diag)
            rhs = np.where(inlet, boundary * length, 0.0)
            # a group touching neither the inlet nor the outlet has no pressure datum: left out
            _, group = csgraph.connected_components(lap != 0, directed=False)
            fixed = np.unique(group[(inlet | outlet) & (k.ravel() > 0)])
            pinned = ~np.isin(group, fixed)
        solve = (k.ravel() > 0) & ~pinned & (np.asarray(abs(lap).sum(axis=1)).ravel() > 0)
        p = np.zeros(n)
        if solve.any():
            p[solve] = spla.spsolve(lap[solve][:, solve].tocsc(), rhs[solve])
        na, nb, nc = faces[axis]
        jump = h if periodic else 0.0
        if periodic:
            out.append(np.sum(nc * (p[na] - p[nb] + jump)) / h / n)
        else:
            width = (rows if axis == 0 else cols) * h
            inflow = np.sum((boundary * (length - p))[inlet & (k.ravel() > 0)])
            outflow = np.sum((boundary * p)[outlet & (k.ravel() > 0)])
            out.append(0.5 * (inflow + outflow) / width)
    return np.array(out)
