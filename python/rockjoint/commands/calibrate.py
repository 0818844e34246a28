# SPDX-License-Identifier: MIT
"""`python3 -m rockjoint calibrate curve.csv --law <law> [...]`: fit a closure law to a measured
loading curve by Levenberg-Marquardt; print the parameters with standard uncertainties and the
residual, write a plot (PNG: data, fit, residuals) and the fitted law as a .rjt table.

The CSV header names the columns and their units, e.g.::

    closure [mm], normal_stress [MPa]
    0.0104, 0.5
    ...

or ``displacement [mm]`` of the jointed specimen with ``--intact-length`` and ``--young`` (the
intact specimen's own deformation σL/E is removed). An optional ``closure_std [mm]`` column
weights the fit by 1/std². See rockjoint.calibration for what each law fits.

With ``--cycles`` the file holds load cycles in test order (loading, unloading, reloading ...):
the law is fitted as the virgin curve of a hysteretic law together with its unloading branches
(permanent fraction r, branch exponent m; rockjoint.cycle_calibration, docs/hysteresis.md) and
the seating offset Δ_0 (the law's closure where the gauges were zeroed; --no-fit-offset: none);
the report gives the rms of each branch, the permanent closure of each cycle and the uncertainties.

With ``--flow`` the file holds flow through the joint along load cycles (rockjoint.flow_cycles:
``normal_stress [MPa]``, optional ``closure [mm]``, ``transmissivity [m3]`` or ``flow_rate
[mL/min]`` with ``pressure_drop [MPa]`` and the test's geometry): the transmissivity law with
history (hydraulic_history over --virgin) is fitted (rockjoint.flow_calibration, docs/flow.md), on
the measured closures, or with the closure law --law fitted together, or a given one
(--closure-law FILE.toml); the report gives the rms of log10 T per branch and what the data
identify; the PNG shows measured and fitted T through the cycle.
"""
from __future__ import annotations

import argparse
from pathlib import Path

from .. import composite_modulus
from ..calibration import calibrate, read_closure_curve
from ..cycle_calibration import calibrate_cycles, read_load_cycles
from ..flow import HISTORY_VIRGINS
from ..flow_calibration import calibrate_flow
from ..flow_cycles import ML_PER_MIN, FlowCycles, FlowGeometry, read_flow_cycles
from ..laws import read_law_file
from ..law_registry import (DEFAULT_TANG_JIAO_BASE, GPA, HEIGHT_DISTRIBUTIONS, MM, MPA, TANG_JIAO_BASES,
                            calibratable)


def add_parser(subparsers) -> None:
    """Register the 'calibrate' command and its options."""
    p = subparsers.add_parser(
        "calibrate", help="fit a closure law to a measured closure curve (CSV)",
        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("curve", help="CSV file: 'closure [mm]' (or 'displacement [mm]') and "
                                 "'normal_stress [MPa]' columns, units in the header")
    p.add_argument("--law", choices=calibratable(),
                   help="law to fit (the calibratable laws of rockjoint.law_registry); required but "
                        "with --flow, where it is the closure law (optional with measured closures)")
    p.add_argument("--young", type=float, metavar="GPA",
                   help="Young's modulus of the rock [GPa] (intact-deformation removal; with "
                        "--poisson it also gives E* = E/(2(1-ν²)) for GW-type laws)")
    p.add_argument("--poisson", type=float, help="Poisson's ratio of the rock [-]")
    p.add_argument("--intact-length", type=float, metavar="MM",
                   help="length of the specimen over which 'displacement' is measured [mm]")
    p.add_argument("--composite-modulus", type=float, metavar="GPA",
                   help="E* [GPa], 1/E* = Σ(1-ν²)/E (GW-type laws; else --young/--poisson)")
    p.add_argument("--summit-radius", type=float, metavar="MM",
                   help="mean summit radius β [mm] (GW-type laws; also R of Eq. (1))")
    p.add_argument("--distribution", choices=HEIGHT_DISTRIBUTIONS, default=HEIGHT_DISTRIBUTIONS[0],
                   help="summit-height distribution of GW-type laws (default gaussian)")
    p.add_argument("--base", choices=TANG_JIAO_BASES, default=DEFAULT_TANG_JIAO_BASE,
                   help=f"base law of tang_jiao (default {DEFAULT_TANG_JIAO_BASE})")
    p.add_argument("--variant", choices=["I1", "I2"], default="I1",
                   help="tang_jiao reading of Eq. (7): I1 stress interaction (default), I2 "
                        "kinematic (docs/theory.md §5)")
    p.add_argument("--base-radius", type=float, metavar="MM",
                   help="substrate base radius r0 [mm] of the Tang base (default 1/(2√η))")
    off = p.add_mutually_exclusive_group()
    off.add_argument("--fit-offset", dest="fit_offset", action="store_true", default=None,
                     help="also fit a closure offset Δ_0 (default for GW-type laws and for "
                          "--cycles: the seating offset)")
    off.add_argument("--no-fit-offset", dest="fit_offset", action="store_false",
                     help="the curve starts at the law's datum, the virgin joint at zero stress "
                          "(default for empirical laws' loading curves)")
    p.add_argument("--cycles", action="store_true",
                   help="the file holds load cycles (test order): fit the law with unloading "
                        "branches (permanent closure, branch exponent)")
    add_flow_arguments(p)
    p.add_argument("--plot", metavar="PNG", help="plot file (default <curve>_<law>.png)")
    p.add_argument("--table", metavar="RJT", help="table file (default <curve>_<law>.rjt)")
    p.add_argument("--max-stress", type=float, metavar="MPA",
                   help="tabulate up to this stress [MPa] (default: the curve's maximum)")
    p.set_defaults(func=run)


def add_flow_arguments(p) -> None:
    """The options of `calibrate --flow` (flow cycles: rockjoint.flow_calibration)."""
    g = p.add_argument_group("flow cycles (--flow)")
    g.add_argument("--flow", action="store_true",
                   help="the file holds flow through load cycles: fit the transmissivity law with history")
    g.add_argument("--virgin", choices=HISTORY_VIRGINS, default=HISTORY_VIRGINS[0],
                   help="transmissivity law of first loading (default cubic_law)")
    g.add_argument("--closure-law", metavar="TOML", help="a closure law parameter file (data without closure; the tabulate "
                        "command's format, its [table] not used)")
    g.add_argument("--geometry", choices=("radial", "linear"), default="radial",
                   help="flow-rate data: radial from a central borehole (default) or linear")
    for name, what in (("inner-radius", "borehole radius r_i"), ("outer-radius", "core radius r_o"),
                       ("width", "width W across linear flow"), ("length", "length L along linear flow")):
        g.add_argument(f"--{name}", type=float, metavar="MM", help=f"{what} [mm]")
    g.add_argument("--pressure-drop", type=float, metavar="MPA", help="Δp [MPa] if the file has no pressure column")
    g.add_argument("--rate", type=float, metavar="ML_MIN", help="Q [mL/min] if the file has no flow-rate column")
    g.add_argument("--flow-alone", action="store_true",
                   help="leave the file's closure column out (a closure that is not the flow path's, e.g. a "
                        "sensor's over a gauge length): the closure law (--law) is fitted with the flow")
    g.add_argument("--viscosity", type=float, default=1.002e-3, metavar="PA_S",
                   help="fluid viscosity [Pa s] (default water at 20 °C)")


def run_flow(args) -> int:
    """Fit the transmissivity law with history to flow cycles (--flow); returns the exit code."""
    rate_data = any(getattr(args, k) is not None for k in ("inner_radius", "outer_radius", "width", "length"))
    geometry = None
    if rate_data:
        mm = {k: None if getattr(args, k) is None else getattr(args, k) * MM
              for k in ("inner_radius", "outer_radius", "width", "length")}
        geometry = FlowGeometry(args.geometry, **mm, viscosity=args.viscosity,
                                pressure_drop=None if args.pressure_drop is None else args.pressure_drop * MPA,
                                flow_rate=None if args.rate is None else args.rate * ML_PER_MIN)
    closure_law = read_law_file(args.closure_law)[0].law if args.closure_law else None
    data = read_flow_cycles(args.curve, geometry)
    if args.flow_alone:
        data = FlowCycles(data.normal_stress, data.transmissivity, None, data.lines, data.source)
    e_star = None if args.composite_modulus is None else args.composite_modulus * GPA
    result = calibrate_flow(data, virgin=args.virgin, law=args.law, closure_law=closure_law,
                            composite_modulus=e_star,
                            summit_radius=None if args.summit_radius is None else args.summit_radius * MM)
    print(result.report())
    plot = Path(args.plot or f"{Path(args.curve).with_suffix('')}_flow.png")
    result.plot(plot)
    print(f"wrote {plot} (measured and fitted transmissivity through the cycle)")
    return 0


def run(args) -> int:
    """Fit the chosen law to the curve in args.curve, print the report; returns the exit code."""
    if args.flow:
        return run_flow(args)
    if args.law is None:
        raise ValueError("--law is required (the law to fit)")
    if args.cycles:
        return run_cycles(args)

    young = args.young * GPA if args.young is not None else None
    curve = read_closure_curve(
        args.curve, intact_length=None if args.intact_length is None else args.intact_length * MM,
        young_modulus=young if args.intact_length is not None else None)
    e_star = None
    if args.composite_modulus is not None:
        e_star = args.composite_modulus * GPA
    elif young is not None and args.poisson is not None:
        e_star = composite_modulus(young, args.poisson)
    result = calibrate(
        curve, args.law, composite_modulus=e_star,
        summit_radius=None if args.summit_radius is None else args.summit_radius * MM,
        distribution=args.distribution, base=args.base, variant=args.variant,
        base_radius=None if args.base_radius is None else args.base_radius * MM,
        fit_offset=args.fit_offset)
    print(result.report())
    stem = Path(args.curve).with_suffix("")
    plot = Path(args.plot or f"{stem}_{args.law}.png")
    table_path = Path(args.table or f"{stem}_{args.law}.rjt")
    result.plot(plot)
    table = result.table(None if args.max_stress is None else args.max_stress * MPA)
    table.save(str(table_path))
    print(f"wrote {plot} (data, fit, residuals) and {table_path} (the fitted law tabulated "
          f"up to {table.knot_stress[-1] * 1e-6:.4g} MPa)")
    return 0


def run_cycles(args) -> int:
    """Fit a law with hysteresis to a multi-cycle closure curve (--cycles); returns the exit code."""
    if args.intact_length is not None:
        raise ValueError("--cycles reads a 'closure' column; remove the intact deformation first")
    e_star = None if args.composite_modulus is None else args.composite_modulus * GPA
    result = calibrate_cycles(read_load_cycles(args.curve), args.law, composite_modulus=e_star,
                              summit_radius=None if args.summit_radius is None
                              else args.summit_radius * MM,
                              fit_offset=True if args.fit_offset is None else args.fit_offset)
    print(result.report())
    return 0
