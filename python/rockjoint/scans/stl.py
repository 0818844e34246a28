# SPDX-License-Identifier: MIT
"""STL meshes of a scanned wall, binary and ASCII. Written here rather than read with meshio
because a scan needs what meshio does not report: the facet or line at which a file is
truncated or holds NaN, and whether the facets form one sheet (non-manifold edges). Binary
STL is a numpy structured read (80-byte header, uint32 count, 50-byte records)."""
from __future__ import annotations

import os

import numpy as np

from .errors import (MalformedScanError, NonFiniteScanError, NonManifoldScanError,
                     TruncatedScanError)
from .points import ScanPoints, finish, metres_per_unit

_RECORD = np.dtype([("normal", "<f4", 3), ("vertices", "<f4", (3, 3)), ("attribute", "<u2")])


def read_stl(path, unit: str = "mm") -> ScanPoints:
    """Read a binary or ASCII STL with coordinates in ``unit``: its distinct vertices (exactly
    equal coordinates merged) and facets. Raises TruncatedScanError, MalformedScanError,
    NonFiniteScanError, NonManifoldScanError (edge in more than two facets, degenerate facet),
    ScanUnitError; each names the file and the facet or line."""
    path = os.fspath(path)
    with open(path, "rb") as fh:
        data = fh.read()
    if len(data) >= 84:
        count = int(np.frombuffer(data, "<u4", 1, 80)[0])
        if len(data) == 84 + 50 * count:
            return _mesh(_binary(path, data, count), path, unit)
    if data.lstrip()[:5].lower() == b"solid":
        return _mesh(_ascii(path, data), path, unit)
    if len(data) < 84:
        raise TruncatedScanError(path, f"{len(data)} bytes: shorter than the 84-byte header "
                                 "of a binary STL and not an ASCII STL ('solid ...')")
    have = (len(data) - 84) / 50
    raise TruncatedScanError(path, f"binary STL header announces {count} facets "
                             f"({84 + 50 * count} bytes), the file has {len(data)} bytes "
                             f"({have:.4g} facets): truncated or not an STL",
                             record=int(have) if have < count else None)


def _binary(path, data: bytes, count: int) -> np.ndarray:
    records = np.frombuffer(data, _RECORD, count, 84)
    vertices = records["vertices"].astype(float)
    bad = ~np.isfinite(vertices).all(axis=(1, 2))
    if bad.any():
        raise NonFiniteScanError(path, "non-finite vertex coordinate",
                                 record=int(np.argmax(bad)))
    return vertices


def _ascii(path, data: bytes) -> np.ndarray:
    """Facets (M, 3, 3) of an ASCII STL; a small state machine so that a fault names its
    line: solid / facet normal / outer loop / 3 vertex / endloop / endfacet / endsolid."""
    try:
        lines = data.decode("ascii").splitlines()
    except UnicodeDecodeError as err:
        raise MalformedScanError(path, f"starts with 'solid' but byte {err.start} is not "
                                 "ASCII, and the size does not fit a binary STL") from None
    facets, current = [], None
    expect = "solid"
    for number, line in enumerate(lines, start=1):
        words = line.split()
        if not words:
            continue
        key = words[0].lower()
        if expect == "solid":
            if key != "solid":
                raise MalformedScanError(path, f"expected 'solid', got '{words[0]}'", line=number)
            expect = "facet"
        elif expect == "facet" and key == "endsolid":
            expect = "done"
            break
        elif key != expect:
            raise MalformedScanError(path, f"expected '{expect}', got '{words[0]}'", line=number)
        elif key == "facet":
            current, expect = [], "outer"
        elif key == "outer":
            expect = "vertex"
        elif key == "vertex":
            if len(words) != 4:
                raise MalformedScanError(path, f"'vertex' needs 3 coordinates, got "
                                         f"{len(words) - 1}", line=number)
            try:
                v = [float(w) for w in words[1:]]
            except ValueError:
                raise MalformedScanError(path, f"vertex coordinates {words[1:]} are not "
                                         "numbers", line=number) from None
            if not np.all(np.isfinite(v)):
                raise NonFiniteScanError(path, "non-finite vertex coordinate", line=number)
            current.append(v)
            expect = "endloop" if len(current) == 3 else "vertex"
        elif key == "endloop":
            expect = "endfacet"
        elif key == "endfacet":
            facets.append(current)
            expect = "facet"
    if expect != "done":
        raise TruncatedScanError(path, f"file ends while expecting '{expect}' after "
                                 f"{len(facets)} complete facets", line=len(lines))
    return np.array(facets, dtype=float).reshape(-1, 3, 3)


def _mesh(facets: np.ndarray, path, unit: str) -> ScanPoints:
    """Merge vertices, refuse degenerate and non-manifold facets (an edge of a single
    scanned sheet belongs to one facet on the boundary, two inside)."""
    if facets.shape[0] == 0:
        raise MalformedScanError(path, "no facets")
    vertices, triangles = np.unique(facets.reshape(-1, 3), axis=0, return_inverse=True)
    triangles = triangles.reshape(-1, 3)
    t = np.sort(triangles, axis=1)
    degenerate = (t[:, 0] == t[:, 1]) | (t[:, 1] == t[:, 2])
    if degenerate.any():
        raise NonManifoldScanError(path, "degenerate facet (two equal vertices)",
                                   record=int(np.argmax(degenerate)))
    edges = np.concatenate([t[:, [0, 1]], t[:, [1, 2]], t[:, [0, 2]]])
    unique, inverse, counts = np.unique(edges, axis=0, return_inverse=True,
                                        return_counts=True)
    over = np.nonzero(counts > 2)[0]
    if over.size:
        e = unique[over[0]]
        facet = int(np.nonzero(inverse.ravel() == over[0])[0][0] % t.shape[0])
        raise NonManifoldScanError(path, f"non-manifold: the edge {vertices[e[0]].tolist()} - "
                                   f"{vertices[e[1]].tolist()} belongs to {counts[over[0]]} "
                                   f"facets ({over.size} such edges); a scanned wall is one "
                                   "sheet", record=facet)
    _check_height_field(path, vertices, triangles)
    return finish(vertices, path, unit, triangles, minimum=3)


# Flipped facets may cover this fraction of the projected area (noise slivers at steep
# spots) before the mesh counts as folded.
FOLD_TOLERANCE = 0.005


def _check_height_field(path, vertices: np.ndarray, triangles: np.ndarray) -> None:
    """A wall is a height field over its mean plane: in a consistently oriented mesh every
    facet faces the same side of that plane. Facets facing the other way are folds or
    overhangs, where one (x, y) has several heights and resampling would mix them; refused
    if they cover more than FOLD_TOLERANCE of the projected area. A mesh whose orientation is
    inconsistent (a directed edge in two facets) cannot be checked this way and is let
    through to the resampling."""
    directed = np.concatenate([triangles[:, [0, 1]], triangles[:, [1, 2]],
                               triangles[:, [2, 0]]])
    if np.unique(directed, axis=0).shape[0] < directed.shape[0]:
        return
    centred = vertices - vertices.mean(axis=0)
    plane_normal = np.linalg.svd(centred, full_matrices=False)[2][2]
    v = vertices[triangles]
    along = np.cross(v[:, 1] - v[:, 0], v[:, 2] - v[:, 0]) @ plane_normal  # 2 x projected area
    minority = along > 0 if np.sum(along[along > 0]) < -np.sum(along[along < 0]) else along < 0
    folded = float(np.sum(np.abs(along[minority])) / np.sum(np.abs(along)))
    if folded > FOLD_TOLERANCE:
        raise NonManifoldScanError(path, f"not a height field: {np.count_nonzero(minority)} "
                                   f"facets ({100 * folded:.1f}% of the projected area) face "
                                   "away from the others (folds or overhangs over the mean "
                                   "plane)", record=int(np.argmax(minority)))


def write_stl(path, points: np.ndarray, triangles: np.ndarray, *, unit: str = "mm",
              binary: bool = True) -> str:
    """Write a triangle mesh ((N, 3) points [m], (M, 3) indices) as STL in ``unit``."""
    v = np.asarray(points, dtype=float)[np.asarray(triangles)] / _metres(unit)
    n = np.cross(v[:, 1] - v[:, 0], v[:, 2] - v[:, 0])
    n /= np.maximum(np.linalg.norm(n, axis=1, keepdims=True), 1e-300)
    if binary:
        rec = np.zeros(v.shape[0], _RECORD)
        rec["normal"], rec["vertices"] = n, v
        with open(path, "wb") as fh:
            fh.write(b"rockjoint scan".ljust(80, b" "))
            fh.write(np.uint32(v.shape[0]).tobytes())
            fh.write(rec.tobytes())
    else:
        with open(path, "w") as fh:
            fh.write("solid wall\n")
            for ni, vi in zip(n, v):
                fh.write(f"  facet normal {ni[0]:.6e} {ni[1]:.6e} {ni[2]:.6e}\n    outer loop\n")
                for p in vi:
                    fh.write(f"      vertex {p[0]:.9e} {p[1]:.9e} {p[2]:.9e}\n")
                fh.write("    endloop\n  endfacet\n")
            fh.write("endsolid wall\n")
    return os.fspath(path)


def _metres(unit: str) -> float:
    return metres_per_unit(unit)
