# SPDX-License-Identifier: MIT
"""`python3 -m rockjoint topography {synth,analyse}`: synthetic joints and the closure-law
parameters of measured or synthetic walls. Lengths in mm, moduli in GPa, stresses in MPa."""
import argparse
import json
import os

import numpy as np

from .. import contact, scans
from .. import topography as topo
from ..laws import RECOMMENDATION, RECOMMENDED, laws_from_topography
from ..scenes import ladder
from ..topography import pyplot, save_figure


def add_parser(subparsers) -> None:
    """Register the 'topography' command and its sub-commands."""
    p = subparsers.add_parser(
        "topography", help="joint-wall topography -> closure-law parameters (η, β, σ_s)",
        description="Synthetic self-affine joints and the summit statistics / closure-law "
                    "parameters of a pair of walls (theory §3). Lengths in mm.")
    sub = p.add_subparsers(dest="topography_command", metavar="action")

    s = sub.add_parser("synth", help="write a synthetic self-affine wall or mated pair")
    s.add_argument("--hurst", type=float, default=0.8, help="Hurst exponent H (0, 1]")
    s.add_argument("--rms", type=float, required=True, help="rms height of a wall [mm]")
    s.add_argument("--shape", type=int, nargs=2, default=(256, 256), metavar=("ROWS", "COLS"))
    s.add_argument("--spacing", type=float, default=0.5, help="grid spacing h [mm]")
    s.add_argument("--rolloff", type=float, default=0.0,
                   help="roll-off wavelength [mm] (0: grid size)")
    s.add_argument("--cutoff", type=float, default=0.0,
                   help="short cut-off wavelength [mm] (0: Nyquist 2h)")
    s.add_argument("--matedness", type=float, default=None,
                   help="matedness wavelength [mm]: write a mated pair (0: identical walls)")
    s.add_argument("--seed", type=int, default=1)
    s.add_argument("--upper", required=True, help="output file of the (upper) wall "
                   "(.txt grid, .xyz, .npy)")
    s.add_argument("--lower", help="output file of the lower wall (with --matedness)")
    s.set_defaults(topography_func=_synth)

    a = sub.add_parser("analyse", help="summit statistics, spectral estimates, resampling, "
                                       "pictures and closure curves of a joint")
    a.add_argument("upper", help="upper wall (or a single wall pressed on a flat)")
    a.add_argument("lower", nargs="?", help="lower wall: same lattice and frame for grids; "
                   "any frame for scans (STL, point clouds, ESRI), which are registered")
    a.add_argument("--format", choices=("auto", "grid", "esri", "stl", "points"),
                   default="auto", help="input format (auto: by extension; .stl scan, "
                   ".asc ESRI if it has an ESRI header, .pts point cloud, else a rockjoint "
                   "grid/.xyz lattice/.npy; unstructured .xyz/.csv clouds need 'points')")
    a.add_argument("--unit", default="mm", help="length unit of scan files (STL, point "
                   "clouds, ESRI grids), which do not say it [default mm]")
    a.add_argument("--spacing", type=float, help="grid spacing [mm] (required for .npy); for "
                   "scans the lattice step they are resampled to (default: sample spacing)")
    a.add_argument("--height-unit", default=None, help="override the height unit of the files")
    a.add_argument("--fill", choices=("none", "nearest", "refuse"), default="none",
                   help="scan nodes not covered by the scan: keep masked (none), copy the "
                        "nearest valid node, or stop with an error; the count is printed")
    a.add_argument("--no-flip", action="store_true",
                   help="the upper scan is already in the joint frame (not seen from above)")
    a.add_argument("--offset", type=int, nargs=2, default=(0, 0), metavar=("DX", "DY"),
                   help="contact state: upper (i, j) faces lower (i+DY, j+DX) [grid steps]")
    a.add_argument("--plane", choices=("common", "separate", "none"), default="common")
    a.add_argument("--resample", type=int, nargs="*", default=[1, 2, 4],
                   help="decimation factors of the resampling study")
    a.add_argument("--figures", help="directory for PNG pictures")
    a.add_argument("--young", type=float, help="Young's modulus of the rock [GPa] "
                                               "(enables the closure laws)")
    a.add_argument("--poisson", type=float, default=0.25, help="Poisson ratio [-]")
    a.add_argument("--stresses", type=float, nargs="*", default=[1, 3, 10, 30],
                   help="normal stresses for the closure table [MPa]")
    a.add_argument("--geometric-area", action="store_true",
                   help="also Tang & Jiao over the measured summits with the geometric overlap "
                        "fraction{e <= Δ} as the contact area of Eq. (2)")
    a.add_argument("--reference", choices=("bem",), default=None,
                   help="also solve the exact elastic contact of the walls (boundary elements) "
                        "and print every law's closure error against it (needs --young)")
    a.add_argument("--bem-kernel", choices=("periodic", "non-periodic"), default="non-periodic",
                   help="half-space kernel of --reference bem: non-periodic for a measured scan "
                        "(default), periodic for a synthetic periodic pair")
    a.add_argument("--json", help="write the parameters to this JSON file")
    a.set_defaults(topography_func=_analyse)
    p.set_defaults(func=run, topography_parser=p)


def run(args) -> int:
    """Run the chosen topography sub-command (help if none); returns the exit code."""
    if not getattr(args, "topography_func", None):
        args.topography_parser.print_help()
        return 2
    return args.topography_func(args)


def _synth(args) -> int:
    spec = topo.SelfAffineSpec(args.hurst, args.rms * 1e-3, args.rolloff * 1e-3,
                               args.cutoff * 1e-3)
    h = args.spacing * 1e-3
    if args.matedness is None:
        if args.lower:
            raise ValueError("--lower needs --matedness (the matedness wavelength of the pair)")
        upper = topo.synthetic_surface(spec, tuple(args.shape), h, args.seed)
        topo.write_surface(args.upper, upper)
        print(f"wrote {args.upper}: {upper.shape[0]} x {upper.shape[1]}, h {args.spacing} mm, "
              f"rms {upper.rms_height * 1e3:.4g} mm, H {args.hurst}")
        return 0
    if not args.lower:
        raise ValueError("--matedness writes a pair: give --lower too")
    upper, lower = topo.mated_pair(spec, tuple(args.shape), h, args.matedness * 1e-3, args.seed)
    topo.write_surface(args.upper, upper)
    topo.write_surface(args.lower, lower)
    print(f"wrote {args.upper} and {args.lower}: {upper.shape[0]} x {upper.shape[1]}, "
          f"h {args.spacing} mm, rms {upper.rms_height * 1e3:.4g} mm, H {args.hurst}, "
          f"matedness wavelength {args.matedness} mm")
    return 0


def _input_kind(path: str, format: str) -> str:
    """'grid' (rockjoint.topography.read_surface) or a scan format of rockjoint.scans."""
    if format != "auto":
        return format
    suffix = os.path.splitext(path)[1].lower()
    if suffix == ".stl":
        return "stl"
    if suffix == ".pts":
        return "points"
    if suffix == ".asc" and os.path.isfile(path) and scans.is_esri_ascii(path):
        return "esri"
    return "grid"


def _read_grid(path, args):
    try:
        return topo.read_surface(path, spacing=args.spacing, height_unit=args.height_unit)
    except ValueError as err:
        if os.path.splitext(path)[1].lower() in (".xyz", ".csv") and "lattice" in str(err):
            raise ValueError(f"{err} (an unstructured point cloud? use --format points)") \
                from None
        raise


def _read_scan(path, kind, args):
    if kind == "grid":   # a lattice wall among scans: its nodes are its samples
        s = _read_grid(path, args)
        return scans.ScanPoints(scans.ScanGrid(s.heights, s.spacing_x, s.spacing_y).points(),
                                path)
    return scans.read_scan(path, kind, unit=args.unit, height_unit=args.height_unit)


def _scan_walls(args, kinds, report):
    """Scans: flip, level, register, resample (rockjoint.scans); returns (upper, joint)."""
    if tuple(args.offset) != (0, 0):
        raise ValueError("scans are registered automatically; --offset is for grids that "
                         "share one lattice")
    spacing = None if args.spacing is None else args.spacing * 1e-3
    upper = _read_scan(args.upper, kinds[0], args)
    if not args.lower:
        flat, _ = scans.level(upper.points)
        grid = scans.resample(flat, spacing or upper.sample_spacing(), path=upper.path)
        heights, holes = scans.apply_fill(grid.heights, args.fill, upper.path)
        print(f"scan {args.upper}: levelled on its mean plane, {heights.shape[0]} x "
              f"{heights.shape[1]} nodes at {grid.spacing_x * 1e3:.4g} mm, {holes} hole "
              f"node(s) ({'masked' if args.fill == 'none' else 'filled: ' + args.fill})")
        surface = topo.Surface(heights, grid.spacing_x, grid.spacing_y)
        return surface, None
    lower = _read_scan(args.lower, kinds[1], args)
    joint = scans.joint_from_scans(upper, lower, spacing=spacing, flip_upper=not args.no_flip,
                                   fill=args.fill, plane_removal=args.plane)
    print(joint.report())
    r = joint.registration
    report["registration"] = {"rotation_deg": float(np.degrees(r.rotation)),
                              "shift_mm": [float(v) * 1e3 for v in r.translation],
                              "overlap_fraction": r.overlap_fraction,
                              "residual_misfit_mm": r.residual_rms * 1e3,
                              "hole_nodes": joint.masked_count, "fill": joint.fill}
    return joint.upper.surface(), joint.composite


def _analyse(args) -> int:
    report = {}
    kinds = [_input_kind(p, args.format) for p in (args.upper, args.lower) if p]
    joint = None
    if any(k != "grid" for k in kinds):
        upper, joint = _scan_walls(args, kinds, report)
    else:
        upper = _read_grid(args.upper, args)
        if args.lower:
            joint = topo.composite_topography(upper, _read_grid(args.lower, args),
                                              tuple(args.offset), args.plane)
    if joint is None:
        # One wall on a flat: the flat is the "upper" wall, so s = z - plane (summits = maxima).
        flat = topo.Surface(np.zeros(upper.shape), upper.spacing_x, upper.spacing_y)
        joint = topo.composite_topography(flat, upper, (0, 0), "separate")
    print(f"contact state: offset {tuple(args.offset)} grid steps, plane removal {args.plane}; "
          f"overlap {joint.aperture.shape[0]} x {joint.aperture.shape[1]} points, "
          f"mean aperture {joint.mean_aperture * 1e3:.4g} mm")
    result = topo.analyse(joint.composite)
    print(result.table())
    study = None
    if args.resample:
        study = topo.resampling_study(joint.composite, args.resample)
        print("\nresampling study (counted | Nayak/McCool from FD moments):")
        print(topo.resampling_table(study))
    report.update({
        "sampling_interval_mm": result.sampling_interval * 1e3,
        "summit_count": result.statistics.summit_count,
        "summit_density_per_mm2": result.statistics.summit_density * 1e-6,
        "summit_radius_mm": result.statistics.summit_radius * 1e3,
        "mean_summit_radius_mm": result.statistics.mean_summit_radius * 1e3,
        "summit_height_std_mm": result.statistics.summit_height_std * 1e3,
        "spectral": {"summit_density_per_mm2": result.spectral.summit_density * 1e-6,
                     "summit_radius_mm": result.spectral.summit_radius * 1e3,
                     "summit_height_std_mm": result.spectral.summit_height_std * 1e3,
                     "bandwidth_alpha": result.spectral.bandwidth},
        "mean_aperture_mm": joint.mean_aperture * 1e3,
    })
    if args.figures:
        os.makedirs(args.figures, exist_ok=True)
        f = args.figures
        paths = [topo.plot_height_map(upper, os.path.join(f, "upper_height.png"), "upper wall"),
                 topo.plot_aperture_map(joint, os.path.join(f, "aperture.png")),
                 topo.plot_summit_histogram(result, os.path.join(f, "summit_heights.png"))]
        try:
            paths.append(topo.plot_power_spectrum(upper, os.path.join(f, "power_spectrum.png"),
                                                  "upper wall power spectrum"))
        except ValueError as err:  # masked grid: no spectrum without inventing points
            print(f"no power spectrum: {err}")
        print("pictures: " + ", ".join(paths))
    if args.young is not None:
        params = topo.closure_parameters(result, young=args.young * 1e9, poisson=args.poisson)
        print(f"\nE* = {params.composite_modulus * 1e-9:.4g} GPa (two walls E {args.young} GPa,"
              f" ν {args.poisson})")
        overlap = topo.overlap_curve(joint.aperture) if args.geometric_area else None
        laws = laws_from_topography(params, summits=result, overlap=overlap)
        stresses = np.array(sorted(args.stresses)) * 1e6
        curves = {key: _closures(named.law, stresses) for key, named in laws.items()}
        bem = None
        if args.reference == "bem":
            bem = contact.closure_curve(joint.aperture, params.composite_modulus, stresses,
                                        periodic=args.bem_kernel == "periodic").closure
            report["bem_closure_mm"] = dict(zip(map(str, sorted(args.stresses)), bem * 1e3))
        print(f"\nrecommended: {RECOMMENDATION}")
        rung = ladder.by_key().get(RECOMMENDED)
        if rung is not None:   # the bench's measured errors (one source: the ladder's JSON)
            print(f"  closure error against the walls' exact contact at half the scan's spacing, "
                  f"{ladder.PREDICTION_LEVEL:.0%} upper prediction limit for a joint of the bench's types "
                  "(the law's own and the scan's resolution error): " + ", ".join(
                f"{family} {100 * e:.1f} %" for family, e in sorted(rung.errors.items())))
        print(f"\nclosure Δ [mm] (laws seated at the measured first contact)"
              + (" and relative error against the BEM reference" if bem is not None else ""))
        print(f"{'law':<42}" + "".join(f"{f'{s:g} MPa':>16}" for s in sorted(args.stresses)))
        if bem is not None:
            print(f"{'exact elastic contact (BEM, ' + args.bem_kernel + ')':<42}"
                  + "".join(f"{v * 1e3:>16.4g}" for v in bem))
        report["closure_mm"] = {}
        for key, named in laws.items():
            row = curves[key]
            report["closure_mm"][key] = dict(zip(map(str, sorted(args.stresses)), row * 1e3))
            cells = [f"{v * 1e3:.4g}" + (f" ({100 * (v / b - 1):+.1f}%)" if bem is not None else "")
                     for v, b in zip(row, bem if bem is not None else row)]
            print(f"{named.label:<42}" + "".join(f"{c:>16}" for c in cells))
        if args.figures:
            print("pictures: " + _plot_closure(os.path.join(args.figures, "closure_curves.png"),
                                               laws, curves, stresses, bem))
    if args.json:
        with open(args.json, "w") as fh:
            json.dump(report, fh, indent=2)
        print(f"parameters: {args.json}")
    return 0


def _closures(law, stresses) -> np.ndarray:
    out = np.full(len(stresses), np.nan)
    for i, s in enumerate(stresses):
        try:
            out[i] = law.closure_at_stress(s)
        except (ValueError, RuntimeError, ArithmeticError):   # beyond a law's validity limit
            pass
    return out


def _plot_closure(path, laws, curves, stresses, bem) -> str:
    """Closure curves of the laws (and the BEM reference) in mm against MPa."""
    plt = pyplot()
    fig, ax = plt.subplots(figsize=(7, 5))
    for key, named in laws.items():
        ax.plot(np.r_[0, curves[key]] * 1e3, np.r_[0, stresses] * 1e-6,
                "-" if key == RECOMMENDED else "--", lw=2 if key == RECOMMENDED else 1,
                label=named.label)
    if bem is not None:
        ax.plot(np.r_[0, bem] * 1e3, np.r_[0, stresses] * 1e-6, "ko-", label="exact elastic (BEM)")
    return save_figure(plt, fig, ax, path, "closure: laws against the exact elastic contact",
                 "closure Δ [mm]", "normal stress σ [MPa]")
