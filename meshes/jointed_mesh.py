# SPDX-License-Identifier: MIT
"""JointedMesh: a conforming simplex mesh of rock blocks with the nodes split along the joints.

The split mesh alone does not say which facets face each other across a joint, so the glue map
(split copy -> original node) and the facet pairs are kept with it and saved with it.

Conventions
- Minus side of a joint facet: the cell whose block has the *lower block tag*; plus side: the other.
  The pair's normal points from minus into plus. Facet node order: ``joint_facets_minus[k]`` is
  ordered so that the right-hand normal points from minus into plus (3D: (x1-x0) x (x2-x0); 2D:
  (t_y, -t_x) with t = x1-x0); ``joint_facets_plus[k]`` lists the plus-side copies *in the same order*
  (glue equal entrywise, coordinates equal pointwise).
- Node ids are 0-based rows of ``points``; nodes 0..n_original-1 are the original (glued) nodes, split
  copies follow. Cells use gmsh/VTK vertex order of linear simplices.
"""
from __future__ import annotations

import json
import os
from dataclasses import dataclass

import numpy as np

FORMAT_NAME = "rockjoint.JointedMesh"
FORMAT_VERSION = 1

_CELL_TYPES = {"triangle": (2, 3), "tetrahedron": (3, 4)}  # name -> (tdim, vertices per cell)
_ARRAYS = ("points", "cells", "cell_blocks", "glue", "joint_facets_minus", "joint_facets_plus",
           "joint_facet_cells", "joint_tags", "boundary_facets", "boundary_tags")


@dataclass
class JointedMesh:
    """A split, conforming mesh of blocks and joints (see the module docstring for conventions).

    points: (n_nodes, gdim) float64 coordinates [m], split copies included.
    cells: (n_cells, nv) int64 linear triangles (2D) or tetrahedra (3D), split node ids.
    cell_type: "triangle" | "tetrahedron".
    cell_blocks: (n_cells,) int32 block tag (physical group of the block).
    glue: (n_nodes,) int64 original (glued) node of each node; glue[i] == i for originals.
    joint_facets_minus: (n_pairs, nvf) int64 nodes of the facet on the minus (lower block tag) side.
    joint_facets_plus: (n_pairs, nvf) int64 plus-side nodes permuted to the minus order.
    joint_facet_cells: (n_pairs, 2) int64 (minus cell, plus cell).
    joint_tags: (n_pairs,) int32 joint tag (physical group of the joint surface).
    boundary_facets: (n_bf, nvf) int64 exterior facets carrying a named boundary group.
    boundary_tags: (n_bf,) int32.
    names: {"blocks": {tag: name}, "joints": {tag: name}, "boundaries": {tag: name}} and optionally
    "joint_sets": {joint tag: set name} (the set of each joint; without it, or for a joint it
    leaves out, a joint is a set of its own: joint_sets()).
    """

    points: np.ndarray
    cells: np.ndarray
    cell_type: str
    cell_blocks: np.ndarray
    glue: np.ndarray
    joint_facets_minus: np.ndarray
    joint_facets_plus: np.ndarray
    joint_facet_cells: np.ndarray
    joint_tags: np.ndarray
    boundary_facets: np.ndarray
    boundary_tags: np.ndarray
    names: dict

    def __post_init__(self):
        self.validate()

    # ---- derived quantities --------------------------------------------------------------
    @property
    def gdim(self) -> int:
        """Geometric dimension of the points (2 or 3)."""
        return int(self.points.shape[1])

    @property
    def tdim(self) -> int:
        """Topological dimension of the cells."""
        return _CELL_TYPES[self.cell_type][0]

    @property
    def num_original_nodes(self) -> int:
        """Number of original (glued) nodes, before the joints were split."""
        return int(np.count_nonzero(self.glue == np.arange(self.glue.size)))

    def tag(self, kind: str, name: str) -> int:
        """Tag of the physical group ``name`` of ``kind`` ("blocks", "joints" or "boundaries")."""
        if kind not in ("blocks", "joints", "boundaries"):
            raise ValueError(f"kind must be 'blocks', 'joints' or 'boundaries', got {kind!r}")
        for tag, n in self.names[kind].items():
            if n == name:
                return int(tag)
        raise KeyError(f"no {kind[:-1] if kind != 'boundaries' else 'boundary'} group named {name!r}; "
                       f"available: {sorted(self.names[kind].values())}")

    def joint_sets(self) -> dict:
        """{joint name: set name} of every joint (a joint without a set is its own)."""
        return joint_sets_of(self.names)

    def cell_measures(self) -> np.ndarray:
        """Area (2D) or volume (3D) of every cell [m^2 or m^3]."""
        x = self.points[self.cells]
        d = x[:, 1:, :] - x[:, :1, :]
        if self.tdim == 2:
            return 0.5 * np.abs(d[:, 0, 0] * d[:, 1, 1] - d[:, 0, 1] * d[:, 1, 0])
        return np.abs(np.einsum("ij,ij->i", d[:, 0], np.cross(d[:, 1], d[:, 2]))) / 6.0

    def block_measures(self) -> dict:
        """{block tag: area or volume} summed over the block's cells."""
        m = self.cell_measures()
        return {int(t): float(m[self.cell_blocks == t].sum()) for t in np.unique(self.cell_blocks)}

    # ---- checks --------------------------------------------------------------------------
    def validate(self) -> None:
        """Check shapes, dtypes, index ranges and the pair invariants; raise ValueError naming the field."""
        if self.cell_type not in _CELL_TYPES:
            raise ValueError(f"JointedMesh.cell_type must be one of {sorted(_CELL_TYPES)}, got {self.cell_type!r}")
        tdim, nv = _CELL_TYPES[self.cell_type]
        self.points = _as(self.points, np.float64, "points", 2)
        if self.points.shape[1] not in (2, 3) or self.points.shape[1] < tdim:
            raise ValueError(f"JointedMesh.points must be (n, {tdim} or 3), got shape {self.points.shape}")
        if not np.all(np.isfinite(self.points)):
            raise ValueError("JointedMesh.points contains NaN or inf")
        n = self.points.shape[0]
        self.cells = _as(self.cells, np.int64, "cells", 2, (None, nv))
        self.cell_blocks = _as(self.cell_blocks, np.int32, "cell_blocks", 1, (self.cells.shape[0],))
        self.glue = _as(self.glue, np.int64, "glue", 1, (n,))
        self.joint_facets_minus = _as(self.joint_facets_minus, np.int64, "joint_facets_minus", 2, (None, nv - 1))
        npairs = self.joint_facets_minus.shape[0]
        self.joint_facets_plus = _as(self.joint_facets_plus, np.int64, "joint_facets_plus", 2, (npairs, nv - 1))
        self.joint_facet_cells = _as(self.joint_facet_cells, np.int64, "joint_facet_cells", 2, (npairs, 2))
        self.joint_tags = _as(self.joint_tags, np.int32, "joint_tags", 1, (npairs,))
        self.boundary_facets = _as(self.boundary_facets, np.int64, "boundary_facets", 2, (None, nv - 1))
        self.boundary_tags = _as(self.boundary_tags, np.int32, "boundary_tags", 1,
                                 (self.boundary_facets.shape[0],))
        for name in ("cells", "glue", "joint_facets_minus", "joint_facets_plus", "boundary_facets"):
            a = getattr(self, name)
            if a.size and (a.min() < 0 or a.max() >= n):
                raise ValueError(f"JointedMesh.{name} has node ids outside [0, {n})")
        if npairs and (self.joint_facet_cells.min() < 0 or self.joint_facet_cells.max() >= self.cells.shape[0]):
            raise ValueError(f"JointedMesh.joint_facet_cells has cell ids outside [0, {self.cells.shape[0]})")
        if np.any(self.glue[self.glue] != self.glue):
            raise ValueError("JointedMesh.glue must map every node to an original node (glue[glue] == glue)")
        if not np.array_equal(self.glue[self.joint_facets_minus], self.glue[self.joint_facets_plus]):
            raise ValueError("JointedMesh.joint_facets_plus is not permuted to the minus order "
                             "(glue of minus and plus facet nodes differ)")
        if np.any(self.joint_facets_minus == self.joint_facets_plus):
            raise ValueError("JointedMesh: a joint facet node is not split (same node on both sides)")
        if not isinstance(self.names, dict) or not ({"blocks", "joints", "boundaries"} <= set(self.names)
                                                    <= {"blocks", "joints", "boundaries", "joint_sets"}):
            raise ValueError("JointedMesh.names must be a dict with keys 'blocks', 'joints', 'boundaries' "
                             "(and optionally 'joint_sets')")
        self.names = {k: {int(t): str(v) for t, v in d.items()} for k, d in self.names.items()}
        stray = set(self.names.get("joint_sets", {})) - set(self.names["joints"])
        if stray:
            raise ValueError(f"JointedMesh.names['joint_sets'] names tags {sorted(stray)} that are no joints")
        for kind, arr in (("blocks", self.cell_blocks), ("joints", self.joint_tags),
                          ("boundaries", self.boundary_tags)):
            unknown = set(np.unique(arr).tolist()) - set(self.names[kind])
            if unknown:
                raise ValueError(f"JointedMesh: {kind} tags {sorted(unknown)} have no name in names[{kind!r}]")

    # ---- persistence ---------------------------------------------------------------------
    def save(self, path: str | os.PathLike) -> None:
        """Write a compressed .npz (arrays + JSON header with format name, version, cell type, names)."""
        path = os.fspath(path)
        if not path.endswith(".npz"):
            raise ValueError(f"JointedMesh.save: the file name must end in .npz, got {path!r}")
        header = {"format": FORMAT_NAME, "version": FORMAT_VERSION, "cell_type": self.cell_type,
                  "names": {k: {str(t): v for t, v in d.items()} for k, d in self.names.items()}}
        np.savez_compressed(path, header=np.array(json.dumps(header)),
                            **{name: getattr(self, name) for name in _ARRAYS})

    @classmethod
    def load(cls, path: str | os.PathLike) -> "JointedMesh":
        """Read a file written by :meth:`save`; OSError if unreadable, ValueError if not a JointedMesh."""
        path = os.fspath(path)
        try:
            data = np.load(path, allow_pickle=False)
        except (OSError, ValueError) as err:
            raise OSError(f"JointedMesh.load: cannot read {path!r}: {err}") from err
        with data:
            if "header" not in data.files:
                raise ValueError(f"JointedMesh.load: {path!r} is not a {FORMAT_NAME} file (no header)")
            try:
                header = json.loads(str(data["header"]))
            except json.JSONDecodeError as err:
                raise ValueError(f"JointedMesh.load: {path!r} has a malformed header: {err}") from err
            if header.get("format") != FORMAT_NAME:
                raise ValueError(f"JointedMesh.load: {path!r} is not a {FORMAT_NAME} file "
                                 f"(format {header.get('format')!r})")
            if header.get("version") != FORMAT_VERSION:
                raise ValueError(f"JointedMesh.load: {path!r} has format version {header.get('version')!r}; "
                                 f"this code reads version {FORMAT_VERSION}")
            missing = [a for a in _ARRAYS if a not in data.files]
            if missing:
                raise ValueError(f"JointedMesh.load: {path!r} lacks the arrays {missing}")
            arrays = {a: data[a] for a in _ARRAYS}
        names = {k: {int(t): v for t, v in d.items()} for k, d in header["names"].items()}
        return cls(cell_type=header["cell_type"], names=names, **arrays)


def joint_sets_of(names: dict) -> dict:
    """{joint name: set name} from a mesh's groups `names` (JointedMesh.names, the distributed
    mesh's): the group "joint_sets" where it names a joint's set, else the joint's own name."""
    sets = names.get("joint_sets", {})
    return {str(n): str(sets.get(t, n)) for t, n in names["joints"].items()}


def _as(a, dtype, name: str, ndim: int, shape: tuple | None = None) -> np.ndarray:
    a = np.asarray(a)
    if a.ndim != ndim:
        raise ValueError(f"JointedMesh.{name} must be {ndim}-dimensional, got shape {a.shape}")
    if np.issubdtype(dtype, np.integer) and a.size and not np.issubdtype(a.dtype, np.integer):
        raise ValueError(f"JointedMesh.{name} must hold integers, got dtype {a.dtype}")
    if shape is not None:
        for i, s in enumerate(shape):
            if s is not None and a.shape[i] != s:
                raise ValueError(f"JointedMesh.{name} must have shape {shape} (None = any), got {a.shape}")
    return np.ascontiguousarray(a, dtype=dtype)
