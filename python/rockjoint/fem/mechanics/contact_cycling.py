# SPDX-License-Identifier: MIT
"""Joint points whose contact cycles between Newton iterates: why a load step stagnates whatever
the load (docs/slopes.md, "Mesh dependence").

A Coulomb strength with cohesion c and a tensile strength T below the apex c / tan φ makes the
shear traction jump where the joint opens: a point in contact sticks with up to
τ_y(-T) = c - T tan φ, an open one carries nothing (docs/joint-strength.md, "Tension cut-off").
Where a point's equilibrium lies at that opening (with T = 0: σ_n → 0, as at a joint's tip on a
free surface), the discrete equations have no solution there: Newton's iterates close the point
(it sticks with its cohesion), open it (it carries nothing), close it again, and the residual
stagnates at a level proportional to the load, so the load stepping gives up at any load and
any strength. Which points do so depends on where the mesh puts them, hence a mesh-dependent
"failure". The record keeps the contact mask of every residual evaluated in the load step being
solved; `hint` names the points that opened and closed at least twice in the last
`window` iterates, their joints and the blocks on both sides, and says what to change."""
from __future__ import annotations

import math

import numpy as np

from ...joint import ShearState, StrengthModel

#: iterates looked at (Newton's stagnation window)
WINDOW = 8
#: points named in a message (the count is given in full)
NAMED = 4


def pair_block_names(dmesh, pairs) -> np.ndarray:
    """(num_pairs, 2) names of the blocks on the minus and plus side of each local joint pair."""
    tags = np.zeros(int(dmesh.cell_blocks.indices.max(initial=-1)) + 1, dtype=np.int64)
    tags[dmesh.cell_blocks.indices] = dmesh.cell_blocks.values
    names = dmesh.names["blocks"]
    cells = np.stack([np.asarray(pairs.minus_cells, dtype=np.int64), np.asarray(pairs.plus_cells, dtype=np.int64)], 1)
    return np.array([[names[int(t)] for t in tags[c]] for c in cells], dtype=object).reshape(-1, 2)


class ContactCycling:
    """The open / in-contact mask of every joint point at each residual of a load step."""

    def __init__(self, window: int = WINDOW):
        self.window = window
        self._masks: list = []

    def clear(self) -> None:
        """A new load step: forget the iterates of the last one."""
        self._masks.clear()

    def record(self, interface) -> None:
        """The contact state of the residual just evaluated."""
        self._masks.append(np.asarray(interface.shear_states()) == int(ShearState.open))
        del self._masks[:-(self.window + 1)]

    def cycling_points(self) -> np.ndarray:
        """Local indices of the points that opened and closed at least twice in the record."""
        if len(self._masks) < 3:
            return np.zeros(0, dtype=int)
        m = np.array(self._masks)
        return np.flatnonzero((m[1:] != m[:-1]).sum(axis=0) >= 2)

    def hint(self, coupling, comm) -> str:
        """Words naming the cycling points (collective; "" if none)."""
        idx = self.cycling_points()
        interface = coupling.interface
        local = []
        if idx.size:
            state = interface.state()
            x = np.asarray(state["coordinates"]).reshape(-1, interface.gdim)
            tags = np.asarray(state["tag"])
            names = {t: n for n, t in coupling.joint_tags.items()}
            pair = idx // (interface.num_points // interface.num_pairs)
            dmesh = coupling.dmesh   # None for bare JointPairs: no block names
            blocks = pair_block_names(dmesh, dmesh.pairs) if dmesh is not None else None
            for i, p in zip(idx, pair):
                sides = sorted(set(blocks[p])) if blocks is not None else ["?"]
                local.append((names[int(tags[i])], tuple(float(v) for v in np.round(x[i], 2)), sides, int(tags[i])))
        # a node shared by two pairs (nodal quadrature) is one point: once, by joint and place
        found = sorted({(j, x): (j, x, b, t) for j, x, b, t in sum(comm.allgather(local), [])}.values())
        if not found:
            return ""
        where = "; ".join(f"joint {j!r} at {x} between {' and '.join(b)}" for j, x, b, _ in found[:NAMED])
        more = f" and {len(found) - NAMED} more" if len(found) > NAMED else ""
        jumps = sorted({j for j, _, _, t in found if _strength_jumps(coupling.behaviours[t].strength)})
        why = (f" The strength of {', '.join(map(repr, jumps))} jumps where it opens (cohesion c > T tan φ: a "
               "point in contact sticks with up to c - T tan φ, an open one carries nothing), so a point whose "
               "equilibrium lies at the opening (σ_n → 0 at a joint's tip on a free surface) has none, at any "
               "load and any strength: give those joints a tensile strength at the apex, T = c / tan φ (the "
               "bond is lost for good where it opens), or no cohesion." if jumps else "")
        return (f"the joints' contact cycles (open, closed, open) at {len(found)} point(s): {where}{more}." + why)


def _strength_jumps(strength) -> bool:
    """True if the shear strength at the opening, c - T tan φ, is above zero (a Coulomb envelope
    cut off before its apex)."""
    if strength.model != StrengthModel.coulomb:
        return strength.model != StrengthModel.none and strength.cohesion > 0.0
    return strength.cohesion - strength.tensile_strength * math.tan(strength.friction_angle) > 1e-9 * max(
        strength.cohesion, 1.0)
