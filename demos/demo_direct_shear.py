#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""A direct-shear laboratory test of a rock joint under constant normal load (CNL).

Read it top to bottom; run it as it is:

    PYTHONPATH=python:build/python /usr/bin/python3 demos/demo_direct_shear.py [--output DIR]

A granite joint (Barton-Bandis closure, constant shear stiffness) is sheared under constant normal
stresses of 0.5, 1, 2 and 4 MPa with the joint strength of docs/joint-strength.md:

1. **The laboratory curve.** The joint of a shear box is one homogeneous point: the shear
   displacement is driven, the normal displacement is found at every step so that the normal
   stress stays at its set value (CNL), and the slip/dilation state is committed after every
   converged step, exactly as the FE model does per quadrature point. Two strengths: Coulomb
   (φ = 30°, c = 0, dilation ψ = 5° up to 2 mm of slip) and Barton (φ_r = 28°, JRC 8, JCS 120 MPa).
   The curves rise elastically (k_s) and level off at the peak, which is marked.
2. **The FE shear box.** The same Coulomb joint between two elastic blocks (plane strain): a
   first stage applies the normal load, then the top of the upper block is displaced
   horizontally stage by stage (displacement control) while the normal load stays; the mean
   shear stress is the top support's reaction over the width. Once the whole joint slips it
   equals the Coulomb peak.

Outputs (in DIR, default the working directory): direct_shear.png (shear stress and normal
displacement against shear displacement), direct_shear_table.txt. Units in print: mm, MPa.
"""
import argparse
import math
import os

import numpy as np
from mpi4py import MPI

import rockjoint
from rockjoint.console import quiet_compiler_logging, say
from rockjoint import meshes
from rockjoint.fem import (JointBehaviour, JointedRockModel, JointPointState, NewtonOptions, distribute,
                           joint_response, make_strength)

COMM = MPI.COMM_WORLD
quiet_compiler_logging()  # DOLFINx's form compiler would log every command



# %% Parameters ------------------------------------------------------------------------------
NORMAL_STRESSES = np.array([0.5, 1.0, 2.0, 4.0]) * 1e6        # CNL levels [Pa]
LAW = rockjoint.BartonBandis(20e9, 0.5e-3)                     # K_ni [Pa/m], V_m [m]
SHEAR_STIFFNESS = 2e9                                          # k_s [Pa/m]
COULOMB = {"model": "coulomb", "friction_angle": math.radians(30.0),
           "dilation_angle": math.radians(5.0), "dilation_limit": 2e-3}
BARTON = {"model": "barton", "friction_angle": math.radians(28.0), "jrc": 8.0, "jcs": 120e6}
MAX_SHEAR_DISPLACEMENT = 5e-3                                  # [m]
STEPS = 100                                                    # point driver steps
FE_STEPS = 10                                                  # FE shear box stages


# %% 1. The laboratory curve: a CNL point driver ---------------------------------------------
def cnl_curve(strength, normal_stress):
    """Shear stress, normal displacement (opening +) and slip along a driven shear displacement
    at constant normal stress; Newton on the normal jump with the law's consistent tangent."""
    behaviour = JointBehaviour(LAW, shear_stiffness=SHEAR_STIFFNESS, strength=make_strength(strength))
    converged = JointPointState()
    jn = -LAW.closure_at_stress(normal_stress)          # seated under the normal load
    rows = []
    for js in np.linspace(0.0, MAX_SHEAR_DISPLACEMENT, STEPS + 1):
        for _ in range(50):
            r = joint_response(behaviour, [jn, js], converged)
            residual = r["traction"][0] + normal_stress  # t_n = -σ_n
            if abs(residual) <= 1e-10 * normal_stress:
                break
            jn -= residual / r["tangent"][0, 0]
        else:
            raise RuntimeError(f"CNL step at shear displacement {js} m did not converge")
        converged = r["state"]                          # commit the converged step
        rows.append((js, r["traction"][1], jn, converged.slip[0]))
    return np.array(rows)


def barton_peak(normal_stress):
    """τ = σ_n tan(φ_r + JRC log10(JCS/σ_n)) (Barton & Choubey 1977), angle capped at 70°."""
    angle = min(28.0 + BARTON["jrc"] * math.log10(BARTON["jcs"] / normal_stress), 70.0)
    return normal_stress * math.tan(math.radians(angle))


# %% 2. The FE shear box ---------------------------------------------------------------------
def fe_curve(normal_stress):
    """The FE shear box (100 mm lower block, 20 mm upper block, plane strain) under CNL: stage 1
    the normal load, then stages that displace the top horizontally (displacement control); the
    shear stress is the top support's horizontal reaction over the width."""
    width = 0.1
    jm = meshes.column(width, 0.12, (0.1,), dim=2, mesh_size=0.01, comm=COMM)
    model = JointedRockModel(distribute(jm, COMM), rock=(50e9, 0.25), joints={"joint_1": LAW},
                             shear_stiffness=SHEAR_STIFFNESS, strength=COULOMB,
                             newton=NewtonOptions(verbose=False))
    model.fix("bottom", "all")
    model.add_traction("top", (0.0, -normal_stress))
    model.solve()
    box = model.fix("top", "x", value=0.0)
    rows = [(0.0, 0.0)]
    for displacement in np.linspace(0.0, MAX_SHEAR_DISPLACEMENT, FE_STEPS + 1)[1:]:
        box.value = displacement
        result = model.solve(load_steps=2)
        rows.append((displacement, result.reactions[("top", "x")] / width))
    return np.array(rows)


def main(out):
    os.makedirs(out, exist_ok=True)
    curves = {}
    table = []
    for sigma in NORMAL_STRESSES:
        coulomb = cnl_curve(COULOMB, sigma)
        barton = cnl_curve(BARTON, sigma)
        fe = fe_curve(sigma)
        curves[sigma] = (coulomb, barton, fe)
        peak_c = sigma * math.tan(COULOMB["friction_angle"])
        table.append((sigma / 1e6, peak_c / 1e6, coulomb[-1, 1] / 1e6, barton_peak(sigma) / 1e6,
                      barton[-1, 1] / 1e6, 1e3 * (coulomb[-1, 2] - coulomb[0, 2]), fe[-1, 1] / 1e6))
        say(f"σ_n = {sigma / 1e6:4.1f} MPa: Coulomb peak {peak_c / 1e6:.4f} MPa (point {coulomb[-1, 1] / 1e6:.4f}, "
            f"FE box {fe[-1, 1] / 1e6:.4f}), Barton peak {barton_peak(sigma) / 1e6:.4f} MPa "
            f"(point {barton[-1, 1] / 1e6:.4f})")
    if COMM.rank != 0:
        return
    header = ("direct shear under constant normal load; columns: normal stress [MPa], Coulomb peak "
              "c + σ tan φ [MPa], Coulomb curve at 5 mm [MPa], Barton peak [MPa], Barton curve at 5 mm "
              "[MPa], Coulomb dilation at 5 mm [mm], FE shear box at 5 mm [MPa]")
    np.savetxt(os.path.join(out, "direct_shear_table.txt"), np.array(table), header=header, fmt="%.10g")

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, (ax, axn) = plt.subplots(1, 2, figsize=(11, 4.5))
    colours = plt.cm.viridis(np.linspace(0.0, 0.85, len(NORMAL_STRESSES)))
    for colour, sigma in zip(colours, NORMAL_STRESSES):
        coulomb, barton, fe = curves[sigma]
        label = f"σ_n = {sigma / 1e6:g} MPa"
        ax.plot(1e3 * coulomb[:, 0], coulomb[:, 1] / 1e6, color=colour, label=f"Coulomb, {label}")
        ax.plot(1e3 * barton[:, 0], barton[:, 1] / 1e6, color=colour, ls="--", label=f"Barton, {label}")
        ax.plot(1e3 * fe[:, 0], fe[:, 1] / 1e6, "o", color=colour, ms=4, mfc="none")
        ax.axhline(sigma * math.tan(COULOMB["friction_angle"]) / 1e6, color=colour, lw=0.6, ls=":")
        ax.plot([1e3 * MAX_SHEAR_DISPLACEMENT], [barton_peak(sigma) / 1e6], "v", color=colour)
        axn.plot(1e3 * coulomb[:, 0], 1e3 * (coulomb[:, 2] - coulomb[0, 2]), color=colour, label=label)
    ax.set_xlabel("shear displacement [mm]")
    ax.set_ylabel("shear stress [MPa]")
    ax.set_title("CNL direct shear: ○ FE shear box (Coulomb), dotted = Coulomb peak,\n▼ = Barton peak",
                 fontsize=10)
    ax.legend(fontsize=7, ncol=2)
    axn.set_xlabel("shear displacement [mm]")
    axn.set_ylabel("normal displacement (dilation) [mm]")
    axn.set_title(f"Coulomb, ψ = {math.degrees(COULOMB['dilation_angle']):g}° up to "
                  f"{1e3 * COULOMB['dilation_limit']:g} mm of slip")
    axn.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "direct_shear.png"), dpi=120)
    say(f"wrote {os.path.join(out, 'direct_shear.png')} and direct_shear_table.txt")


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[1])
    parser.add_argument("--output", default=".", help="output directory")
    main(parser.parse_args().output)
