# SPDX-License-Identifier: MIT
"""The checks of JointedRockModel's inputs (rock, density, element, plane): each names the
argument, the block and the valid range; the model keeps only what they return."""
from __future__ import annotations

import numpy as np

from ...validation import positive_number
from ..mesh.distributed_mesh import names_of


def per_block(blocks: dict, value, what: str, missing_message: str) -> dict:
    """{block name: value} from one value for every block or a dict that names them all."""
    if not isinstance(value, dict):
        return {b: value for b in blocks}
    unknown = set(value) - set(blocks)
    if unknown:
        raise ValueError(f"{what}: unknown block(s) {sorted(unknown)}; available blocks: {sorted(blocks)}")
    missing = set(blocks) - set(value)
    if missing:
        raise ValueError(f"{what}: " + missing_message.format(sorted(missing)))
    return value


def check_rock(dmesh, rock) -> dict:
    """{block tag: (E [Pa], ν)} from {block name: (E, ν)} or one (E, ν) for every block."""
    blocks = names_of(dmesh, "blocks")
    if rock is None:
        raise ValueError(f"rock properties are missing; give rock={{block: (E, nu)}} for blocks {sorted(blocks)}")
    rock = per_block(blocks, rock, "rock", "no (E, nu) for block(s) {}")
    out = {}
    for name, value in rock.items():
        try:
            E, nu = (float(v) for v in value)
        except (TypeError, ValueError):
            raise ValueError(f"rock[{name!r}] must be (E [Pa], nu), got {value!r}") from None
        if not (np.isfinite(E) and E > 0):
            raise ValueError(f"rock[{name!r}]: Young's modulus E = {E} Pa is invalid; it must be finite and > 0")
        if not (-1.0 < nu < 0.5):
            raise ValueError(f"rock[{name!r}]: Poisson's ratio nu = {nu} is invalid; it must be in (-1, 0.5)")
        out[blocks[name]] = (E, nu)
    return out


def check_density(dmesh, density) -> dict:
    """{block name: ρ [kg/m³]} ({} for None: no gravity)."""
    if density is None:
        return {}
    density = per_block(names_of(dmesh, "blocks"), density, "density",
                        "no value for block(s) {} (give one for every block)")
    return {name: positive_number(f"density[{name!r}]", rho, unit="kg/m³") for name, rho in density.items()}


def check_element(element_degree: int, quadrature: str) -> int:
    """The element degree (1 or 2); ValueError for another or for degree 2 without the nodal quadrature."""
    if element_degree not in (1, 2):
        raise ValueError(f"element_degree must be 1 or 2, got {element_degree!r}")
    if element_degree == 2 and quadrature != "nodal":
        raise ValueError("element_degree=2 supports the 'nodal' joint quadrature only")
    return element_degree


def check_plane(gdim: int, plane: str | None) -> str | None:
    """"strain" (default) or "stress" in 2D; None in 3D."""
    if gdim == 2:
        plane = "strain" if plane is None else plane
        if plane not in ("strain", "stress"):
            raise ValueError(f"plane must be 'strain' or 'stress' in 2D, got {plane!r}")
        return plane
    if plane not in (None, "3D", "3d"):
        raise ValueError(f"plane={plane!r} is meaningless in 3D; pass plane=None")
    return None
