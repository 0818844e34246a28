# SPDX-License-Identifier: MIT
"""The direct-shear demo runs as it is, and its curves level off at the closed-form peaks:
Coulomb σ_n tan 30°, Barton σ_n tan(28° + 8 log10(120 MPa/σ_n)), dilation tan 5° × 2 mm; the FE
shear box (displacement control under constant normal load) levels off at the Coulomb peak."""
import math

import numpy as np

from fe_stack import require_fe  # noqa: E402
require_fe()

import demo_runner  # noqa: E402


def test_direct_shear_demo_reproduces_the_peaks(tmp_path):
    demo_runner.run_demo("demo_direct_shear.py", tmp_path)
    assert (tmp_path / "direct_shear.png").exists()
    table = np.loadtxt(tmp_path / "direct_shear_table.txt", comments="#", ndmin=2)
    sigma = table[:, 0]
    np.testing.assert_allclose(sigma, [0.5, 1.0, 2.0, 4.0])
    coulomb = sigma * math.tan(math.radians(30.0))
    barton = sigma * np.tan(np.radians(28.0 + 8.0 * np.log10(120.0 / sigma)))
    np.testing.assert_allclose(table[:, 1], coulomb, rtol=1e-6)
    np.testing.assert_allclose(table[:, 2], coulomb, rtol=1e-6)
    np.testing.assert_allclose(table[:, 4], barton, rtol=1e-6)
    np.testing.assert_allclose(table[:, 5], math.tan(math.radians(5.0)) * 2.0, rtol=1e-6)
    # The FE shear box, fully slipping at 5 mm: its mean shear stress is the Coulomb peak.
    np.testing.assert_allclose(table[:, 6], coulomb, rtol=1e-8)
