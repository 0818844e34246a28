# SPDX-License-Identifier: MIT
"""One unit table: the lengths the C++ topography parser accepts are those of scene files, law
parameter files and calibration curves, with the same factors (checked against the SI
definitions written out here), and the law registry's units are entries of the same table."""
import pytest

from rockjoint import law_registry, units
from rockjoint import topography as topo
from rockjoint.calibration import _LENGTH_UNITS
from rockjoint.scenes.units import parse_quantity

#: SI definitions of the length units (metres per unit)
SI_LENGTH = {"m": 1.0, "cm": 0.01, "mm": 0.001, "um": 1e-6, "µm": 1e-6, "micron": 1e-6, "nm": 1e-9,
             "km": 1000.0}


def test_every_reader_takes_the_same_length_units():
    assert units.DIMENSIONS["length"] == SI_LENGTH
    for unit, metres in SI_LENGTH.items():
        assert topo.metres_per_unit(unit) == metres                        # the C++ parser
        assert parse_quantity(f"2 {unit}", "length") == pytest.approx(2 * metres, rel=1e-15)  # scenes
        assert _LENGTH_UNITS[unit] == metres                               # calibration curves
    with pytest.raises(ValueError, match="furlong"):
        topo.metres_per_unit("furlong")
    with pytest.raises(ValueError, match="furlong"):
        parse_quantity("2 furlong", "length")


def test_law_units_are_entries_of_the_table():
    assert law_registry.UNITS == {"-": 1.0, "mm": 1e-3, "MPa": 1e6, "GPa": 1e9, "MPa/mm": 1e9, "1/mm²": 1e6}
    for unit, dimension in units.LAW_UNIT_DIMENSION.items():
        assert law_registry.UNITS[unit] == units.DIMENSIONS[dimension][unit]
