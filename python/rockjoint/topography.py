# SPDX-License-Identifier: MIT
"""Joint-wall topography -> closure-law parameters (theory §3; Xia et al. 2003 contact state).

SI units inside (heights and spacings in m, η in 1/m², β and σ_s in m); files and pictures
say their units (mm by default). The numerics are in C++ (``rockjoint._rockjoint.topography``);
this module owns the defaults, the .npy I/O, the statistics the laws take and the pictures.

Typical use::

    upper = read_surface("upper.txt")            # or synthetic walls: mated_pair(...)
    lower = read_surface("lower.txt")
    joint = composite_topography(upper, lower, offset=(0, 0))
    result = analyse(joint.composite)            # counted and spectral η, β, σ_s at h
    params = closure_parameters(result, young=50e9, poisson=0.25)  # AsperityParameters
    laws = rockjoint.laws.laws_from_topography(params, summits=result)  # GW, Tang, Tang & Jiao
"""
from __future__ import annotations

import dataclasses
import math
import os
from typing import Dict, Iterable, Optional, Sequence, Tuple, Union

import numpy as np

from ._rockjoint import topography as _cpp
from ._rockjoint.constitutive import AsperityParameters, composite_modulus
from .scans.esri import is_esri_ascii, read_esri_ascii  # scans sit below: they read files into Surfaces
from .scans.frame import plane_removal_mode

Surface = _cpp.Surface
CompositeTopography = _cpp.CompositeTopography
SummitStatistics = _cpp.SummitStatistics
NayakEstimates = _cpp.NayakEstimates
SpectralMoments = _cpp.SpectralMoments  # the type of NayakEstimates.moments
PlaneRemoval = _cpp.PlaneRemoval
Window = _cpp.Window
ApertureDistribution = _cpp.ApertureDistribution
decimate = _cpp.decimate
curvature_field = _cpp.curvature_field
finite_difference_moments = _cpp.finite_difference_moments
psd_moments = _cpp.psd_moments
nayak_estimates = _cpp.nayak_estimates
metres_per_unit = _cpp.metres_per_unit
#: (SummitStatistics, summits) of a surface: 8-neighbour summits, their 5-point curvature and
#: the counted η, β, σ_s (the first step of analyse)
analyse_summits = _cpp.analyse_summits

PathLike = Union[str, "os.PathLike[str]"]

_GRID_SUFFIXES = (".txt", ".grid", ".asc", ".dat")
_XYZ_SUFFIXES = (".xyz", ".csv")


# ---- files -----------------------------------------------------------------------------------
def read_surface(path: PathLike, *, spacing: Optional[float] = None,
                 spacing_y: Optional[float] = None, lateral_unit: Optional[str] = None,
                 height_unit: Optional[str] = None) -> Surface:
    """Read a height map: plain-text grid (.txt/.grid/.asc/.dat), ESRI ASCII grid (.asc
    starting with an ESRI header key; units default to mm), XYZ list on a lattice (.xyz/.csv)
    or NumPy array (.npy, NaN = missing). Scans (STL, unstructured XYZ): rockjoint.scans.

    ``spacing`` (in ``lateral_unit``) and the units override what the file says. A .npy file
    holds only heights, so ``spacing`` is required there; its units default to mm.
    Errors (ValueError) name the file and line; a missing file raises FileNotFoundError.
    """
    path = os.fspath(path)
    if not os.path.isfile(path):
        raise FileNotFoundError(f"no such height-map file: '{path}'")
    suffix = os.path.splitext(path)[1].lower()
    if suffix == ".npy":
        if spacing is None:
            raise ValueError(f"{path}: a .npy file holds heights only; pass spacing= "
                             "(grid step, in lateral_unit)")
        heights = np.load(path, allow_pickle=False)
        if heights.ndim != 2:
            raise ValueError(f"{path}: expected a 2D array of heights, got shape {heights.shape}")
        if not np.issubdtype(heights.dtype, np.number):
            raise ValueError(f"{path}: heights must be numbers, got dtype {heights.dtype}")
        lat = metres_per_unit(lateral_unit or "mm")
        hgt = metres_per_unit(height_unit or "mm")
        sy = spacing if spacing_y is None else spacing_y
        return Surface(heights.astype(float) * hgt, spacing * lat, sy * lat)
    if suffix in _XYZ_SUFFIXES:
        if spacing is not None:
            raise ValueError(f"{path}: an XYZ list defines its own lattice; do not pass spacing")
        return _cpp.read_xyz(path, lateral_unit=lateral_unit, height_unit=height_unit)[0]
    if suffix == ".asc" and _is_esri_ascii(path):
        # ESRI ASCII grid (any header variant, rockjoint.scans.esri); it states no units
        if spacing is not None or spacing_y is not None:
            raise ValueError(f"{path}: an ESRI ASCII grid states its cell size; do not pass "
                             "spacing")
        return read_esri_ascii(path, unit=lateral_unit or "mm",
                               height_unit=height_unit).surface()
    if suffix in _GRID_SUFFIXES:
        return _cpp.read_height_grid(path, spacing_x=spacing, spacing_y=spacing_y,
                                     lateral_unit=lateral_unit, height_unit=height_unit)[0]
    raise ValueError(f"{path}: unknown height-map format '{suffix}'; use one of "
                     f"{', '.join(_GRID_SUFFIXES + _XYZ_SUFFIXES)}, .npy")


def _is_esri_ascii(path: str) -> bool:
    return is_esri_ascii(path)


def write_surface(path: PathLike, surface: Surface, *, lateral_unit: str = "mm",
                  height_unit: str = "mm") -> str:
    """Write a height map in the format of the suffix (see read_surface). A .npy file gets
    the heights in ``height_unit`` only: keep the spacing yourself."""
    path = os.fspath(path)
    suffix = os.path.splitext(path)[1].lower()
    if suffix == ".npy":
        np.save(path, surface.heights / metres_per_unit(height_unit))
    elif suffix in _XYZ_SUFFIXES:
        _cpp.write_xyz(path, surface, lateral_unit, height_unit)
    elif suffix in _GRID_SUFFIXES:
        _cpp.write_height_grid(path, surface, lateral_unit, height_unit)
    else:
        raise ValueError(f"{path}: unknown height-map format '{suffix}'")
    return path


# ---- synthetic joints ------------------------------------------------------------------------
@dataclasses.dataclass(frozen=True)
class SelfAffineSpec:
    """A self-affine wall (SI units). Spectrum C(q) flat below q_r = 2π/λ_r, ∝ q^{-2(1+H)}
    from q_r to q_s = 2π/λ_s, zero beyond (self_affine.hpp)."""

    hurst_exponent: float = 0.8
    rms_height: float = 1e-3          # [m]
    rolloff_wavelength: float = 0.0   # λ_r [m]; 0 = grid size (no plateau)
    cutoff_wavelength: float = 0.0    # λ_s [m]; 0 = Nyquist 2h


def synthetic_surface(spec: SelfAffineSpec, shape: Tuple[int, int], spacing: float,
                      seed: int = 1, exact_rms: bool = True) -> Surface:
    """One Gaussian self-affine wall, deterministic for a seed (mt19937_64 + Box-Muller)."""
    rows, cols = shape
    return _cpp.self_affine_surface(spec.hurst_exponent, spec.rms_height, rows, cols, spacing,
                                    seed, spec.rolloff_wavelength, spec.cutoff_wavelength,
                                    exact_rms)


def mated_pair(spec: SelfAffineSpec, shape: Tuple[int, int], spacing: float,
               matedness_wavelength: float, seed: int = 1,
               exact_rms: bool = True) -> Tuple[Surface, Surface]:
    """(upper, lower) walls sharing every Fourier component of wavelength >= λ_m; below λ_m
    the lower wall has an independent component of the same spectrum. λ_m = 0: identical."""
    rows, cols = shape
    return _cpp.mated_pair(spec.hurst_exponent, spec.rms_height, rows, cols, spacing, seed,
                           matedness_wavelength, spec.rolloff_wavelength,
                           spec.cutoff_wavelength, exact_rms)


# ---- contact state ---------------------------------------------------------------------------
def composite_topography(upper: Surface, lower: Surface, offset: Tuple[int, int] = (0, 0),
                         plane_removal: Union[str, PlaneRemoval] = "common"
                         ) -> CompositeTopography:
    """Register the walls (offset = (dx, dy) grid steps: upper (i, j) faces lower
    (i + dy, j + dx)), remove a least-squares plane ("common", "separate" or "none"), form the
    aperture e = z_u - z_l shifted to first contact (min e = 0) and s = mean(e) - e."""
    return _cpp.composite_topography(upper, lower, int(offset[0]), int(offset[1]),
                                     plane_removal_mode(plane_removal))


def overlap_ratio(aperture: Surface, closure) -> Union[float, np.ndarray]:
    """Geometric overlap ratio fraction{e <= Δ} [-] at closure(s) Δ [m] (theory §3).

    Four points with apertures 0, 0.1, 0.2 and 0.3 mm: a closure of 0.15 mm brings half of them
    into overlap, one of 0.3 mm all of them.

    >>> import numpy as np
    >>> aperture = Surface(np.array([[0.0, 1e-4], [2e-4, 3e-4]]), 1e-3)
    >>> [float(r) for r in overlap_ratio(aperture, [0.0, 1.5e-4, 3e-4])]
    [0.25, 0.5, 1.0]
    """
    return ApertureDistribution(aperture).overlap_ratio(np.asarray(closure, dtype=float))


# ---- summit statistics -----------------------------------------------------------------------
@dataclasses.dataclass
class TopographyAnalysis:
    """Counted and spectral summit statistics of one surface at one sampling interval."""

    statistics: SummitStatistics      # counted: η, β = 1/mean κ, σ_s, ... (SI)
    summits: Dict[str, np.ndarray]    # rows, cols, heights [m], curvatures [1/m]
    spectral: NayakEstimates          # Nayak/McCool from finite-difference moments
    spectral_psd: Optional[NayakEstimates]  # ... from the 2D periodogram (complete grids)

    @property
    def sampling_interval(self) -> float:
        """h [m] the parameters belong to (η ~ h⁻², β ~ h^1.1)."""
        return max(self.statistics.sampling_interval_x, self.statistics.sampling_interval_y)

    @property
    def summit_radii(self) -> np.ndarray:
        """Per-summit radii 1/κ [m]."""
        return 1.0 / self.summits["curvatures"]

    def table(self) -> str:
        """Counted vs spectral η [1/mm²], β [mm], σ_s [mm] at h [mm]."""
        st = self.statistics
        rows = [("counted (8-neighbour)", st.summit_density, st.summit_radius,
                 st.summit_height_std)]
        rows.append(("Nayak/McCool, FD moments", self.spectral.summit_density,
                     self.spectral.summit_radius, self.spectral.summit_height_std))
        if self.spectral_psd is not None:
            rows.append(("Nayak/McCool, 2D PSD", self.spectral_psd.summit_density,
                         self.spectral_psd.summit_radius, self.spectral_psd.summit_height_std))
        lines = [f"sampling interval h = {self.sampling_interval * 1e3:.4g} mm, "
                 f"{st.summit_count} summits on {st.scanned_area * 1e6:.4g} mm², "
                 f"surface rms {st.surface_rms * 1e3:.4g} mm, "
                 f"mean per-summit radius {st.mean_summit_radius * 1e3:.4g} mm",
                 f"{'estimate':<26} {'η [1/mm²]':>10} {'β [mm]':>9} {'σ_s [mm]':>9}"]
        for name, eta, beta, sig in rows:
            lines.append(f"{name:<26} {eta * 1e-6:>10.4g} {beta * 1e3:>9.4g} {sig * 1e3:>9.4g}")
        return "\n".join(lines)


def analyse(surface: Surface, *, window: Union[str, Window] = "hann") -> TopographyAnalysis:
    """Summits (8-neighbour), curvature (5-point), η, β, σ_s, and the Nayak/McCool estimates
    from finite-difference moments and, if the grid is complete, from the 2D PSD."""
    window = getattr(Window, window) if isinstance(window, str) else window
    statistics, summits = analyse_summits(surface)
    h = max(surface.spacing_x, surface.spacing_y)
    spectral = nayak_estimates(finite_difference_moments(surface), h)
    spectral_psd = None
    if surface.valid_count == surface.shape[0] * surface.shape[1]:
        spectral_psd = nayak_estimates(psd_moments(surface, window), h)
    return TopographyAnalysis(statistics, summits, spectral, spectral_psd)


def resampling_study(surface: Surface, factors: Sequence[int] = (1, 2, 4, 8)):
    """η, β, σ_s (counted and spectral) at h, 2h, 4h, ... (every k-th point)."""
    return _cpp.resampling_study(surface, list(factors))


def resampling_table(rows) -> str:
    """The resampling study as a text table (mm units)."""
    out = [f"{'h [mm]':>7} {'summits':>8} {'η [1/mm²]':>10} {'β [mm]':>8} {'σ_s [mm]':>9}"
           f" | {'η_N [1/mm²]':>11} {'β_N [mm]':>9} {'σ_s,N [mm]':>10}"]
    for r in rows:
        s, n = r.summits, r.spectral
        out.append(f"{r.sampling_interval * 1e3:>7.3g} {s.summit_count:>8d} "
                   f"{s.summit_density * 1e-6:>10.4g} {s.summit_radius * 1e3:>8.4g} "
                   f"{s.summit_height_std * 1e3:>9.4g} | {n.summit_density * 1e-6:>11.4g} "
                   f"{n.summit_radius * 1e3:>9.4g} {n.summit_height_std * 1e3:>10.4g}")
    return "\n".join(out)


@dataclasses.dataclass
class HurstEstimate:
    """A power-law fit C = C0 (q/q_ref)^(-2(1+H)) to the radially averaged spectrum of a surface.

    Fields: hurst_exponent H [-], slope d ln C / d ln q [-] and its standard error,
    log_prefactor (ln C [m⁴] at q = 1 rad/m), the band [q_min, q_max] [rad/m] fitted, and the
    radial spectrum itself: q [rad/m], psd [m⁴] and the number of modes in each bin.
    """

    hurst_exponent: float
    slope: float
    slope_std_error: float
    log_prefactor: float
    q_min: float          # [rad/m]
    q_max: float          # [rad/m]
    q: np.ndarray         # radial spectrum [rad/m]
    psd: np.ndarray       # [m⁴]
    count: np.ndarray


def hurst_estimate(surface: Surface, *, wavelength_range: Optional[Tuple[float, float]] = None,
                   window: Union[str, Window] = "hann") -> HurstEstimate:
    """Fit C ∝ q^{-2(1+H)} to the radially averaged spectrum over wavelengths
    [λ_min, λ_max] [m] (default: 4 h to a quarter of the grid size)."""
    window = getattr(Window, window) if isinstance(window, str) else window
    q, c, n = _cpp.radial_spectrum(surface, window)
    h = max(surface.spacing_x, surface.spacing_y)
    size = min(surface.shape[0] * surface.spacing_y, surface.shape[1] * surface.spacing_x)
    lmin, lmax = wavelength_range or (4.0 * h, size / 4.0)
    fit = _cpp.fit_hurst_exponent(q, c, n, 2 * math.pi / lmax, 2 * math.pi / lmin)
    return HurstEstimate(fit.hurst_exponent, fit.slope, fit.slope_std_error,
                         fit.log_prefactor, fit.q_min, fit.q_max, q, c, n)


# ---- straight into the laws ------------------------------------------------------------------
def closure_parameters(analysis: TopographyAnalysis, *, young: float, poisson: float,
                       young_lower: Optional[float] = None,
                       poisson_lower: Optional[float] = None,
                       source: str = "counted") -> AsperityParameters:
    """The roughness statistics of an analysed composite as rockjoint.AsperityParameters:
    η, β, σ_s counted (``source="counted"``) or the Nayak/McCool estimates from FD moments
    (``"spectral"``), the sampling interval h they belong to, and E* from the walls' E [Pa] and
    ν (both walls alike unless the lower wall's are given). Laws from them: rockjoint.laws."""
    if young_lower is None and poisson_lower is None:
        e_star = composite_modulus(young, poisson)
    else:
        e_star = composite_modulus(young, poisson, young_lower or young,
                                   poisson if poisson_lower is None else poisson_lower)
    if source == "counted":
        return _cpp.asperity_parameters(analysis.statistics, e_star)
    if source == "spectral":
        return _cpp.asperity_parameters(analysis.spectral, e_star)
    raise ValueError(f"source '{source}' is not 'counted' or 'spectral'")


def empirical_summits(analysis: TopographyAnalysis) -> Tuple[np.ndarray, np.ndarray, float]:
    """The measured summit list in the form the asperity laws take as an empirical
    distribution: (heights above the mean plane of the composite [m], per-summit radii [m],
    scanned area A0 [m²]), so that η = N/A0."""
    if analysis.statistics.summit_count < 2:
        raise ValueError(f"{analysis.statistics.summit_count} summit(s): no empirical "
                         "distribution (zero closure capacity)")
    return (np.array(analysis.summits["heights"], dtype=float), analysis.summit_radii,
            float(analysis.statistics.scanned_area))


# ---- pictures (matplotlib, Agg, PNG; lengths in mm) ------------------------------------------
def pyplot():
    """matplotlib.pyplot on the Agg backend (PNG files, no display)."""
    import matplotlib  # optional and slow to import: only when a picture is drawn
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    return plt


def save_figure(plt, fig, ax, path: PathLike, title: str, xlabel: str, ylabel: str,
          legend: bool = True) -> str:
    """Label (units in the labels), save as PNG and close a one-axes figure; returns the path."""
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    ax.set_title(title)
    if legend:
        ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(os.fspath(path), dpi=120)
    plt.close(fig)
    return os.fspath(path)


def _extent_mm(surface: Surface):
    rows, cols = surface.shape
    return (0.0, (cols - 1) * surface.spacing_x * 1e3, 0.0, (rows - 1) * surface.spacing_y * 1e3)


def _map(surface: Surface, path: PathLike, title: str, label: str, cmap: str) -> str:
    plt = pyplot()
    fig, ax = plt.subplots(figsize=(6, 5))
    cm = plt.get_cmap(cmap).copy()
    cm.set_bad("0.8")  # missing points: grey, never interpolated
    im = ax.imshow(np.ma.masked_invalid(surface.heights * 1e3), origin="lower",
                   extent=_extent_mm(surface), cmap=cm, interpolation="nearest")
    fig.colorbar(im, ax=ax, label=label)
    return save_figure(plt, fig, ax, path, title, "x [mm]", "y [mm]", legend=False)


def plot_height_map(surface: Surface, path: PathLike, title: str = "height map") -> str:
    """Height map (mm) as PNG; missing points grey."""
    return _map(surface, path, title, "height [mm]", "terrain")


def plot_aperture_map(joint: CompositeTopography, path: PathLike,
                      title: str = "aperture e = z_u - z_l (first contact: min e = 0)") -> str:
    """Aperture field (mm) of a contact state as PNG."""
    return _map(joint.aperture, path, title, "aperture [mm]", "viridis")


def plot_summit_histogram(analysis: TopographyAnalysis, path: PathLike,
                          title: str = "summit heights") -> str:
    """Histogram of summit heights (mm) with the fitted Gaussian (mean, σ_s) and an
    exponential fitted to the upper tail, the summits that make contact first (z above the
    mean μ: density p_tail e^{-(z-μ)/λ}/λ, maximum likelihood λ = mean(z - μ | z > μ))."""
    plt = pyplot()
    z = analysis.summits["heights"] * 1e3
    if z.size < 2:
        raise ValueError(f"{z.size} summit(s): nothing to histogram")
    mean, std = float(np.mean(z)), float(np.std(z, ddof=1))
    tail = z[z > mean]
    p_tail = tail.size / z.size
    scale = float(np.mean(tail - mean)) if tail.size else float("nan")
    fig, ax = plt.subplots(figsize=(6, 4))
    counts, _, _ = ax.hist(z, bins=min(60, max(10, int(np.sqrt(z.size)))), density=True,
                           color="0.75", label=f"{z.size} summits")
    t = np.linspace(z.min() - std, z.max() + std, 400)
    ax.plot(t, np.exp(-0.5 * ((t - mean) / std) ** 2) / (std * math.sqrt(2 * math.pi)),
            label=f"Gaussian: mean {mean:.3g}, σ_s {std:.3g} mm")
    ax.set_ylim(0.0, 1.4 * float(np.max(counts)))
    if tail.size:
        te = t[t >= mean]
        ax.plot(te, p_tail * np.exp(-(te - mean) / scale) / scale,
                label=f"exponential upper tail: scale {scale:.3g} mm")
    return save_figure(plt, fig, ax, path, title, "summit height above the mean plane [mm]",
                 "probability density [1/mm]")


def plot_power_spectrum(surface: Surface, path: PathLike, title: str = "power spectrum",
                        estimate: Optional[HurstEstimate] = None, **fit_options) -> str:
    """Radially averaged PSD (q in rad/mm, C in mm⁴) with the fitted power law and its H."""
    plt = pyplot()
    est = estimate or hurst_estimate(surface, **fit_options)
    fig, ax = plt.subplots(figsize=(6, 4))
    ax.loglog(est.q * 1e-3, est.psd * 1e12, ".", ms=3, color="0.4", label="radial average")
    qf = np.geomspace(est.q_min, est.q_max, 50)
    ax.loglog(qf * 1e-3, np.exp(est.log_prefactor) * qf ** est.slope * 1e12, "r-",
              label=f"fit: slope {est.slope:.3f}, H = {est.hurst_exponent:.3f}"
                    f" ± {est.slope_std_error / 2:.3f}")
    return save_figure(plt, fig, ax, path, title, "wavenumber q [rad/mm]", "PSD C(q) [mm⁴]")


def overlap_curve(aperture: Surface, maximum_closure: Optional[float] = None,
                  samples: int = 200) -> Tuple[np.ndarray, np.ndarray]:
    """Samples (Δ [m], fraction{e <= Δ} [-]) of the geometric overlap ratio from Δ = 0 up to
    ``maximum_closure`` (default: the mean aperture, the largest closure the walls admit),
    in the form TangJiao(overlap_closure=, overlap_area_ratio=) takes for Eq. (2)."""
    e = aperture.heights
    top = float(np.nanmean(e)) if maximum_closure is None else float(maximum_closure)
    if not top > 0:
        raise ValueError("the aperture is identically 0: no overlap curve (no closure capacity)")
    closure = np.linspace(0.0, top, samples)
    return closure, np.asarray(overlap_ratio(aperture, closure), dtype=float)
