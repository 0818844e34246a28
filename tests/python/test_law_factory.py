# SPDX-License-Identifier: MIT
"""The one law factory (rockjoint.laws) and the one parameter type (AsperityParameters):
laws by name, from a parameter file and from a topography, checked against closed forms."""
import math
import re

import numpy as np
import pytest

import rockjoint
from rockjoint import laws as rl
from rockjoint import topography as topo

E_STAR, ETA, BETA, SIGMA_S = 26.7e9, 0.3e6, 2.5e-3, 0.05e-3
PARAMS = rockjoint.AsperityParameters(composite_modulus=E_STAR, summit_density=ETA,
                                      summit_radius=BETA, summit_height_std=SIGMA_S)


def test_parameter_type_validates_and_keeps_the_sampling_interval():
    p = rockjoint.AsperityParameters(E_STAR, ETA, BETA, SIGMA_S, sampling_interval=0.5e-3)
    assert p.sampling_interval == 0.5e-3 and PARAMS.sampling_interval is None
    assert "sampling_interval=0.0005" in repr(p)
    for name in ("composite_modulus", "summit_density", "summit_radius", "summit_height_std",
                 "sampling_interval"):
        values = dict(composite_modulus=E_STAR, summit_density=ETA, summit_radius=BETA,
                      summit_height_std=SIGMA_S, sampling_interval=1e-3)
        values[name] = -1.0 if name != "summit_radius" else float("nan")
        with pytest.raises(ValueError, match=f"'{name}'"):
            rockjoint.AsperityParameters(**values)


def test_gw_exponential_by_name_matches_the_closed_form():
    # Theory §2: exponential heights (z >= 0), σ(d) = √π E* η β^½ σ_s^{3/2} e^{-d/σ_s} for
    # d >= 0; seated at d0 the law gives σ(d0 - Δ) - σ(d0).
    d0 = 8.0 * SIGMA_S
    law = rl.make_law("greenwood_williamson", PARAMS, distribution="exponential",
                      reference_separation=d0)
    closure = np.array([1e-6, 2e-5, 1e-4])
    expected = (math.sqrt(math.pi) * E_STAR * ETA * math.sqrt(BETA) * SIGMA_S**1.5
                * math.exp(-d0 / SIGMA_S) * np.expm1(closure / SIGMA_S))
    np.testing.assert_allclose(law.normal_stress(closure), expected, rtol=1e-10)


def test_substrate_default_is_the_centre_deflection_coefficient():
    # κ_s = 8/(3π) (uniform base load, centre deflection: theory §4) unless given.
    law = rl.make_law("tang_substrate", PARAMS)
    assert law.deflection_coefficient == pytest.approx(8.0 / (3.0 * math.pi), rel=1e-15)
    assert rl.make_law("tang_substrate", PARAMS, deflection_coefficient=2 / 3) \
        .deflection_coefficient == pytest.approx(2 / 3)


def test_by_name_errors_name_the_problem():
    with pytest.raises(ValueError, match="unknown law model 'gw'"):
        rl.make_law("gw", PARAMS)
    with pytest.raises(ValueError, match="tang_jiao: AsperityParameters are required"):
        rl.make_law("tang_jiao")       # the law the user named, not its default base
    with pytest.raises(ValueError, match="apply to tang_jiao only"):
        rl.make_law("greenwood_williamson", PARAMS, variant="I2")


def test_parameter_file_gives_the_named_law(tmp_path):
    path = tmp_path / "tj.toml"
    path.write_text('[law]\nmodel = "tang_jiao"\nyoung_modulus_GPa = 50\npoisson_ratio = 0.25\n'
                    'summit_density_per_mm2 = 0.3\nsummit_radius_mm = 2.5\n'
                    'summit_height_std_mm = 0.05\nsampling_interval_mm = 0.5\n'
                    '[table]\nmaximum_stress_MPa = 30\n')
    named, options = rl.read_law_file(path)
    assert (named.key, named.label) == ("tang_jiao", "Tang & Jiao")
    assert options["max_stress"] == 30e6 and options["tolerance"] == 1e-6
    e_star = 50e9 / (2.0 * (1.0 - 0.25**2))  # theory §1, two walls of one rock
    direct = rockjoint.TangJiao(rockjoint.TangSubstrate(e_star, 0.3e6, 2.5e-3, 0.05e-3))
    d = np.linspace(1e-5, 2e-4, 5)
    np.testing.assert_allclose(named.law.normal_stress(d), direct.normal_stress(d), rtol=1e-13)
    path.write_text('[law]\nmodel = "barton_bandis"\nmaximum_closure_mm = 0.3\n'
                    '[table]\nmaximum_stress_MPa = 30\n')
    with pytest.raises(ValueError, match="missing initial_normal_stiffness_MPa_per_mm"):
        rl.read_law_file(path)


def test_every_registered_model_is_listed():
    text = rl.describe_models()
    for key in ("barton_bandis", "logarithmic", "exponential", "greenwood_williamson",
                "tang_substrate", "tang_jiao"):
        assert len(re.findall(rf"^{key}:", text, re.M)) == 1


def test_laws_from_topography_are_named_objects_keyed_by_identifier():
    u, l = topo.mated_pair(topo.SelfAffineSpec(0.8, 1e-3), (96, 96), 0.5e-3, 2.5e-3, seed=3)
    joint = topo.composite_topography(u, l)
    result = topo.analyse(joint.composite)
    params = topo.closure_parameters(result, young=50e9, poisson=0.25)
    assert isinstance(params, rockjoint.AsperityParameters)
    assert params.sampling_interval == 0.5e-3
    laws = rl.laws_from_topography(params, summits=result,
                                   overlap=topo.overlap_curve(joint.aperture))
    assert set(laws) == {"greenwood_williamson", "tang_substrate", "tang_jiao", rl.RECOMMENDED,
                         "greenwood_williamson_empirical", "tang_substrate_empirical",
                         "tang_jiao_empirical", "tang_jiao_empirical_geometric"}
    for key, named in laws.items():
        assert named.key == key and named.label and named.description
        assert isinstance(named.law, rockjoint.ClosureLaw)
    with pytest.raises(ValueError, match="give summits= too"):
        rl.laws_from_topography(params, overlap=topo.overlap_curve(joint.aperture))


def test_topography_laws_are_seated_at_the_measured_first_contact_by_default():
    u, l = topo.mated_pair(topo.SelfAffineSpec(0.8, 1e-3), (96, 96), 0.5e-3, 2.5e-3, seed=5)
    result = topo.analyse(topo.composite_topography(u, l).composite)
    params = topo.closure_parameters(result, young=50e9, poisson=0.25)
    z = result.summits["heights"]
    d = np.linspace(1e-6, 1e-4, 6)
    first = rl.laws_from_topography(params, summits=result, empirical=False)
    seated = rockjoint.GreenwoodWilliamson(params.composite_modulus, params.summit_density,
                                           params.summit_radius, params.summit_height_std,
                                           reference_separation=z.max() - z.mean())
    np.testing.assert_allclose(first["greenwood_williamson"].law.normal_stress(d),
                               seated.normal_stress(d), rtol=1e-14)
    old = rl.laws_from_topography(params, seating="mean+3.5")
    default = rockjoint.GreenwoodWilliamson(params.composite_modulus, params.summit_density,
                                            params.summit_radius, params.summit_height_std)
    np.testing.assert_allclose(old["greenwood_williamson"].law.normal_stress(d),
                               default.normal_stress(d), rtol=1e-14)
    assert set(first) == {"greenwood_williamson", "tang_substrate", "tang_jiao", rl.RECOMMENDED}
    assert "bench/results/accuracy_ladder.md" in first[rl.RECOMMENDED].description
    with pytest.raises(ValueError, match="needs summits="):
        rl.laws_from_topography(params)
