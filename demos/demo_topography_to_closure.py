#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""From joint-wall topography to closure curves: a granite-like and a sandstone-like joint.

Read top to bottom; run as it is:

    PYTHONPATH=<build>/python /usr/bin/python3 demos/demo_topography_to_closure.py [--output DIR]

It prints the parameter tables (η, β, σ_s at 0.5 mm sampling, counted and spectral), the
resampling study, the closures at a few stresses, and writes PNG pictures to DIR
(default demos/output/topography). Units: mm, MPa, GPa in print and pictures; SI inside.
"""
import argparse
import os

import numpy as np

import rockjoint
from rockjoint import topography as topo

# %% The two joints ---------------------------------------------------------------------------
# Both are 100 mm x 100 mm laboratory specimens scanned at h = 0.5 mm (200 x 200 points), as
# in Tang & Jiao (2018), whose parameters come from such scans (Xia et al. 2003 contact state).
#
# Granite-like: a fresh tensile fracture in a fine/medium-grained crystalline rock. Walls are
# strongly persistent (H = 0.8, the value most profilometry of granite fractures reports) with
# 1.0 mm rms over the specimen, and tightly mated: the walls differ only below a matedness
# wavelength of 2.5 mm (a few grain sizes).
# Sandstone-like: a grain-dominated, less persistent surface (H = 0.65), smoother overall
# (0.6 mm rms) but worse mated (6 mm: grain plucking and crushing during fracture).
# E and ν are mid-range values of theory §7 (granite 30-70 GPa, sandstone 5-30 GPa).
SPACING = 0.5e-3
SHAPE = (200, 200)
JOINTS = {
    "granite-like": dict(spec=topo.SelfAffineSpec(hurst_exponent=0.8, rms_height=1.0e-3),
                         matedness=2.5e-3, young=50e9, poisson=0.25, seed=1),
    "sandstone-like": dict(spec=topo.SelfAffineSpec(hurst_exponent=0.65, rms_height=0.6e-3),
                           matedness=6.0e-3, young=15e9, poisson=0.20, seed=2),
}
STRESSES_MPA = [1, 3, 10, 30]


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--output", default=os.path.join(os.path.dirname(os.path.abspath(__file__)),
                                                     "output", "topography"))
    out = ap.parse_args().output
    os.makedirs(out, exist_ok=True)

    results = {}
    for name, joint in JOINTS.items():
        print(f"\n=== {name} joint ===")
        # %% Walls and contact state ---------------------------------------------------------
        # A mated pair: identical above the matedness wavelength, independent below it. The
        # mated contact state is offset (0, 0); the composite topography s = mean(e) - e of the
        # aperture e (shifted to first contact) is what the closure laws see.
        upper, lower = topo.mated_pair(joint["spec"], SHAPE, SPACING, joint["matedness"],
                                       seed=joint["seed"])
        state = topo.composite_topography(upper, lower, offset=(0, 0))
        # The synthetic walls are periodic, so no taper is needed (window="none"); for
        # measured walls keep the default Hann window.
        fit = topo.hurst_estimate(upper, window="none")
        print(f"walls: rms {upper.rms_height * 1e3:.3g} mm, fitted H "
              f"{fit.hurst_exponent:.3f} ± {fit.slope_std_error / 2:.3f} "
              f"(requested {joint['spec'].hurst_exponent}); mean aperture "
              f"{state.mean_aperture * 1e3:.3g} mm")

        # %% Summit statistics at h = 0.5 mm -------------------------------------------------
        # Counted: 8-neighbour summits, 5-point curvature, β = 1/mean κ. Spectral: Nayak/McCool
        # from finite-difference and 2D-PSD moments, side by side.
        analysis = topo.analyse(state.composite)
        print(analysis.table())

        # %% How the parameters move with the sampling interval ------------------------------
        # η ~ h⁻², β ~ h^1.1 (theory §3): a parameter set is only meaningful with its h.
        print("resampling study:")
        print(topo.resampling_table(topo.resampling_study(state.composite, [1, 2, 4])))

        # %% Straight into the laws ----------------------------------------------------------
        # E* = E / (2(1-ν²)) for two walls of one rock. GW and Tang on the Gaussian fit
        # (η, β, σ_s), Tang & Jiao I1 over Tang; the measured summit list feeds the
        # empirical variants (each summit with its own radius, seated at first contact).
        # The geometric overlap fraction{e <= Δ} is offered as the area of Eq. (2) for the
        # empirical Tang & Jiao law: it ignores elastic deformation, so it is an upper bound
        # on the contact area and the interaction correction it drives is the largest one.
        params = topo.closure_parameters(analysis, young=joint["young"],
                                         poisson=joint["poisson"])
        overlap = topo.overlap_curve(state.aperture)
        for d_mm in (0.02, 0.05, 0.1):
            print(f"geometric overlap fraction{{e <= {d_mm} mm}} = "
                  f"{topo.overlap_ratio(state.aperture, d_mm * 1e-3):.4f}")
        laws = rockjoint.laws.laws_from_topography(params, summits=analysis, overlap=overlap)
        print(f"E* = {params.composite_modulus * 1e-9:.4g} GPa; closure Δ [mm] at σ [MPa]:")
        print(f"{'law':<42}" + "".join(f"{s:>10g}" for s in STRESSES_MPA))
        for named in laws.values():
            row = []
            for s in STRESSES_MPA:
                try:
                    row.append(named.law.closure_at_stress(s * 1e6) * 1e3)
                except (ValueError, ArithmeticError, RuntimeError):
                    row.append(float("nan"))  # beyond the law's validity limit
            print(f"{named.label:<42}" + "".join(f"{v:>10.4g}" for v in row))

        # %% Pictures ------------------------------------------------------------------------
        tag = name.split("-")[0]
        topo.plot_height_map(upper, os.path.join(out, f"{tag}_upper_wall.png"),
                             f"{name}: upper wall")
        topo.plot_aperture_map(state, os.path.join(out, f"{tag}_aperture.png"),
                               f"{name}: aperture (mated, first contact)")
        topo.plot_summit_histogram(analysis, os.path.join(out, f"{tag}_summit_heights.png"),
                                   f"{name}: composite summit heights")
        topo.plot_power_spectrum(upper, os.path.join(out, f"{tag}_power_spectrum.png"),
                                 f"{name}: upper wall power spectrum", estimate=fit)
        results[name] = dict(analysis=analysis, laws=laws, state=state)

    # %% The parameters table ------------------------------------------------------------------
    print("\nParameters at h = 0.5 mm (counted | Nayak/McCool from FD moments):")
    print(f"{'joint':<16}{'η [1/mm²]':>11}{'β [mm]':>9}{'σ_s [mm]':>10} |"
          f"{'η_N':>8}{'β_N':>8}{'σ_s,N':>8}")
    for name, r in results.items():
        st, sp = r["analysis"].statistics, r["analysis"].spectral
        print(f"{name:<16}{st.summit_density * 1e-6:>11.3f}{st.summit_radius * 1e3:>9.3f}"
              f"{st.summit_height_std * 1e3:>10.4f} |{sp.summit_density * 1e-6:>8.3f}"
              f"{sp.summit_radius * 1e3:>8.3f}{sp.summit_height_std * 1e3:>8.4f}")

    # %% Closure curves, one PNG --------------------------------------------------------------
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, len(results), figsize=(11, 4.5))
    stress = np.linspace(0.0, STRESSES_MPA[-1], 121)[1:] * 1e6
    for ax, (name, r) in zip(np.atleast_1d(axes), results.items()):
        for key, named in r["laws"].items():
            closure = []
            for s in stress:
                try:
                    closure.append(named.law.closure_at_stress(s))
                except (ValueError, ArithmeticError, RuntimeError):
                    closure.append(np.nan)
            # colour = model, solid = Gaussian (η, β, σ_s), dashed = measured summit list;
            # Tang & Jiao is drawn dotted on top: at A/A0 ~ 1 % it sits on the Tang curve.
            empirical, geometric = "empirical" in key, "geometric" in key
            colour = {"greenwood_williamson": "C0", "tang_substrate": "C1", "tang_jiao": "C2",
                      rockjoint.laws.RECOMMENDED: "C4"}[
                key.replace("_empirical", "").replace("_geometric", "")]
            style = ":" if key.startswith("tang_jiao") else ("--" if empirical else "-")
            if geometric:
                colour, style = "C3", "-."
            ax.plot(np.r_[0.0, closure] * 1e3, np.r_[0.0, stress] * 1e-6, style, color=colour,
                    lw=2.2 if style == ":" else 1.5,
                    alpha=1.0 if not empirical or geometric else 0.7, label=named.label)
        st = r["analysis"].statistics
        ax.set_title(f"{name}: η {st.summit_density * 1e-6:.2f}/mm², β "
                     f"{st.summit_radius * 1e3:.2f} mm, σ_s {st.summit_height_std * 1e3:.3f} mm",
                     fontsize=9)
        ax.set_xlabel("closure Δ [mm]")
        ax.set_ylabel("normal stress σ [MPa]")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8)
    fig.tight_layout()
    path = os.path.join(out, "closure_curves.png")
    fig.savefig(path, dpi=120)
    plt.close(fig)
    print(f"\npictures in {out} (closure curves: {path})")


if __name__ == "__main__":
    main()
