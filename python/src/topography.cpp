// SPDX-License-Identifier: MIT
// Bindings of rockjoint::topography (SI units: heights and spacings in metres). The pure
// Python layer rockjoint/topography.py owns the defaults, the .npy I/O and the pictures.
#include "array_helpers.hpp"

#include <algorithm>
#include <optional>

#include <rockjoint/topography/closure_parameters.hpp>
#include <rockjoint/topography/composite.hpp>
#include <rockjoint/topography/overlap.hpp>
#include <rockjoint/topography/power_spectrum.hpp>
#include <rockjoint/topography/self_affine.hpp>
#include <rockjoint/topography/spectral_moments.hpp>
#include <rockjoint/topography/summits.hpp>
#include <rockjoint/topography/surface.hpp>
#include <rockjoint/topography/surface_io.hpp>
#include <rockjoint/topography/units.hpp>

#include <pybind11/eigen.h>
#include <pybind11/stl.h>

namespace py = pybind11;
using namespace rockjoint::topography;

namespace rockjoint::python
{

namespace
{
using GridArray = py::array_t<double, py::array::c_style | py::array::forcecast>;

HeightGrid to_grid(const GridArray& a)
{
  if (a.ndim() != 2)
    throw py::value_error("heights must be a 2D array (rows = y, columns = x), got "
                          + std::to_string(a.ndim()) + " dimensions");
  HeightGrid g(a.shape(0), a.shape(1));
  std::copy(a.data(), a.data() + a.size(), g.data());
  return g;
}

GridArray to_array(const HeightGrid& g)
{
  GridArray a({g.rows(), g.cols()});
  std::copy(g.data(), g.data() + g.size(), a.mutable_data());
  return a;
}

template <class T>
py::array_t<T> vector_array(const std::vector<T>& v)
{
  return py::array_t<T>(static_cast<py::ssize_t>(v.size()), v.data());
}

ReadOptions read_options(std::optional<double> sx, std::optional<double> sy,
                         std::optional<std::string> lateral, std::optional<std::string> height)
{
  ReadOptions o;
  o.spacing_x = sx;
  o.spacing_y = sy ? sy : sx;
  o.lateral_unit = lateral;
  o.height_unit = height;
  return o;
}

py::tuple file_tuple(const SurfaceFile& f)
{
  return py::make_tuple(f.surface, f.lateral_unit, f.height_unit);
}
} // namespace

void declare_topography(py::module_& m)
{
  py::class_<Surface>(m, "Surface",
                      "Heights [m] on a regular lattice (row i: y = i*spacing_y; column j: "
                      "x = j*spacing_x); NaN = missing point")
      .def(py::init([](const GridArray& h, double sx, std::optional<double> sy)
                    { return Surface(to_grid(h), sx, sy.value_or(sx)); }),
           py::arg("heights"), py::arg("spacing_x"), py::arg("spacing_y") = py::none())
      .def_property_readonly("heights", [](const Surface& s) { return to_array(s.heights()); },
                             "Copy of the heights [m] (rows = y, columns = x)")
      .def_property_readonly("spacing_x", &Surface::spacing_x, "[m]")
      .def_property_readonly("spacing_y", &Surface::spacing_y, "[m]")
      .def_property_readonly("shape", [](const Surface& s)
                             { return py::make_tuple(s.rows(), s.cols()); },
                             "(rows, columns) of the lattice, like numpy's")
      .def_property_readonly("valid_count", &Surface::valid_count, "Number of valid (non-NaN) points.")
      .def_property_readonly("mean_height", &Surface::mean_height, "[m]")
      .def_property_readonly("rms_height", &Surface::rms_height, "[m]")
      .def("__repr__", [](const Surface& s)
           {
             return "Surface(" + std::to_string(s.rows()) + " x " + std::to_string(s.cols())
                    + ", spacing " + std::to_string(s.spacing_x() * 1e3) + " x "
                    + std::to_string(s.spacing_y() * 1e3) + " mm)";
           });
  m.def("decimate", &decimate, py::arg("surface"), py::arg("factor"),
        "Every factor-th point: the same surface sampled factor times more coarsely");
  m.def("metres_per_unit", &metres_per_unit, py::arg("unit"),
        "Metres per length unit `unit` (a name of length_units()); ValueError naming the unit "
        "and the valid ones otherwise");
  m.def(
      "length_units",
      []()
      {
        py::dict out;
        for (const LengthUnit& u : length_units())
          out[py::str(std::string(u.name))] = u.metres;
        return out;
      },
      "{unit: metres}: every length unit rockjoint reads (the one table, topography/units.cpp)");

  // ---- files -----------------------------------------------------------------------------
  m.def("read_height_grid",
        [](const std::string& p, std::optional<double> sx, std::optional<double> sy,
           std::optional<std::string> lu, std::optional<std::string> hu)
        { return file_tuple(read_height_grid(p, read_options(sx, sy, lu, hu))); },
        py::arg("path"), py::arg("spacing_x") = py::none(), py::arg("spacing_y") = py::none(),
        py::arg("lateral_unit") = py::none(), py::arg("height_unit") = py::none(),
        "(Surface, lateral_unit, height_unit) from a plain-text height grid");
  m.def("write_height_grid", &write_height_grid, py::arg("path"), py::arg("surface"),
        py::arg("lateral_unit") = "mm", py::arg("height_unit") = "mm");
  m.def("read_xyz",
        [](const std::string& p, std::optional<std::string> lu, std::optional<std::string> hu)
        { return file_tuple(read_xyz(p, read_options({}, {}, lu, hu))); },
        py::arg("path"), py::arg("lateral_unit") = py::none(),
        py::arg("height_unit") = py::none(),
        "(Surface, lateral_unit, height_unit) from an XYZ list on a regular lattice");
  m.def("write_xyz", &write_xyz, py::arg("path"), py::arg("surface"),
        py::arg("lateral_unit") = "mm", py::arg("height_unit") = "mm");

  // ---- synthesis -------------------------------------------------------------------------
  m.def("self_affine_surface",
        [](double H, double rms, Eigen::Index rows, Eigen::Index cols, double h,
           std::uint64_t seed, double lr, double ls, bool exact)
        { return self_affine_surface({H, rms, lr, ls}, {rows, cols, h, seed, exact}); },
        py::arg("hurst_exponent"), py::arg("rms_height"), py::arg("rows"), py::arg("cols"),
        py::arg("spacing"), py::arg("seed"), py::arg("rolloff_wavelength") = 0.0,
        py::arg("cutoff_wavelength") = 0.0, py::arg("exact_rms") = true,
        py::call_guard<py::gil_scoped_release>());
  m.def("mated_pair",
        [](double H, double rms, Eigen::Index rows, Eigen::Index cols, double h,
           std::uint64_t seed, double lm, double lr, double ls, bool exact)
        { return mated_pair({H, rms, lr, ls}, {rows, cols, h, seed, exact}, lm); },
        py::arg("hurst_exponent"), py::arg("rms_height"), py::arg("rows"), py::arg("cols"),
        py::arg("spacing"), py::arg("seed"), py::arg("matedness_wavelength"),
        py::arg("rolloff_wavelength") = 0.0, py::arg("cutoff_wavelength") = 0.0,
        py::arg("exact_rms") = true, py::call_guard<py::gil_scoped_release>());

  // ---- composite topography --------------------------------------------------------------
  py::enum_<PlaneRemoval>(m, "PlaneRemoval", "How the mean planes of two walls are removed")
      .value("common", PlaneRemoval::common,
             "one plane fitted to both walls, subtracted from both (the default)")
      .value("separate", PlaneRemoval::separate, "each wall its own plane (walls scanned apart)")
      .value("none", PlaneRemoval::none, "heights used as given");
  py::class_<Plane>(m, "Plane", "z = offset + slope_x x + slope_y y [m]")
      .def_readonly("offset", &Plane::offset, "z at x = y = 0 [m]")
      .def_readonly("slope_x", &Plane::slope_x, "dz/dx [-]")
      .def_readonly("slope_y", &Plane::slope_y, "dz/dy [-]");
  py::class_<CompositeTopography>(m, "CompositeTopography",
                                  "Two walls registered on their overlap lattice and the fields "
                                  "derived from them: aperture e and composite surface [m]")
      .def_readonly("upper", &CompositeTopography::upper, "upper wall after registration and plane removal [m]")
      .def_readonly("lower", &CompositeTopography::lower, "lower wall, registered, plane removed [m]")
      .def_readonly("aperture", &CompositeTopography::aperture, "e = z_u - z_l - min(z_u - z_l) >= 0, NaN where either is missing [m]")
      .def_readonly("composite", &CompositeTopography::composite, "s = mean(e) - e [m]; max s = mean(e) at the first contact")
      .def_readonly("mean_aperture", &CompositeTopography::mean_aperture, "mean(e) [m] = the largest closure the walls admit")
      .def_readonly("interpenetration", &CompositeTopography::interpenetration, "-min(z_u - z_l) before the shift [m] (> 0: walls overlap as given)")
      .def_readonly("upper_plane", &CompositeTopography::upper_plane, "plane removed from the upper wall")
      .def_readonly("lower_plane", &CompositeTopography::lower_plane, "plane removed from the lower wall (in the overlap frame)")
      .def_property_readonly("offset", [](const CompositeTopography& c)
                             { return py::make_tuple(c.state.offset_x, c.state.offset_y); },
                             "(offset_x, offset_y) [grid steps] of the lower wall against the upper");
  m.def("composite_topography",
        [](const Surface& u, const Surface& l, int ox, int oy, PlaneRemoval p)
        { return composite_topography(u, l, {ox, oy, p}); },
        py::arg("upper"), py::arg("lower"), py::arg("offset_x") = 0, py::arg("offset_y") = 0,
        py::arg("plane_removal") = PlaneRemoval::common);

  // ---- summits ---------------------------------------------------------------------------
  py::class_<SummitStatistics>(m, "SummitStatistics",
                               "GW statistics of a surface's summits, counted on its lattice, "
                               "with the sampling interval they belong to")
      .def_readonly("sampling_interval_x", &SummitStatistics::sampling_interval_x, "h_x [m]")
      .def_readonly("sampling_interval_y", &SummitStatistics::sampling_interval_y, "h_y [m]")
      .def_readonly("summit_count", &SummitStatistics::summit_count, "summits found")
      .def_readonly("eligible_points", &SummitStatistics::eligible_points, "points whose 8 neighbours are all valid")
      .def_readonly("scanned_area", &SummitStatistics::scanned_area, "eligible_points · h_x h_y [m²]")
      .def_readonly("summit_density", &SummitStatistics::summit_density, "η = summit_count / scanned_area [1/m²]")
      .def_readonly("summit_radius", &SummitStatistics::summit_radius, "β = 1/mean(κ) [m] (NaN without summits)")
      .def_readonly("mean_summit_radius", &SummitStatistics::mean_summit_radius, "mean(1/κ) [m], the per-summit alternative")
      .def_readonly("mean_curvature", &SummitStatistics::mean_curvature, "mean(κ) [1/m]")
      .def_readonly("summit_height_std", &SummitStatistics::summit_height_std, "σ_s, sample std (n-1) of summit heights [m]")
      .def_readonly("mean_summit_height", &SummitStatistics::mean_summit_height, "mean summit height above the mean plane [m]")
      .def_readonly("highest_summit", &SummitStatistics::highest_summit, "max summit height above the mean plane [m]")
      .def_readonly("surface_rms", &SummitStatistics::surface_rms, "σ, rms of the surface heights [m]");
  m.def("analyse_summits",
        [](const Surface& s)
        {
          SummitAnalysis a;
          {
            py::gil_scoped_release release;
            a = analyse_summits(s);
          }
          py::dict list;
          list["rows"] = vector_array(a.summits.rows);
          list["cols"] = vector_array(a.summits.cols);
          list["heights"] = vector_array(a.summits.heights);
          list["curvatures"] = vector_array(a.summits.curvatures);
          return py::make_tuple(a.statistics, list);
        },
        py::arg("surface"), "(SummitStatistics, dict of arrays rows, cols, heights [m], "
                            "curvatures [1/m])");
  m.def("curvature_field", [](const Surface& s) { return to_array(curvature_field(s)); },
        py::arg("surface"),
        "κ = -½∇²s [1/m] at every point with a complete 5-point stencil, NaN elsewhere");

  // ---- spectra ---------------------------------------------------------------------------
  py::enum_<Window>(m, "Window", "Window applied to the heights before a periodogram")
      .value("none", Window::none, "no window")
      .value("hann", Window::hann, "Hann window (the default)");
  py::class_<SpectralMoments>(m, "SpectralMoments",
                              "Profile spectral moments m0 [m²], m2 [-], m4 [1/m²]")
      .def_readonly("m0", &SpectralMoments::m0, "m0 = σ² [m²]")
      .def_readonly("m2", &SpectralMoments::m2, "(m2x + m2y)/2")
      .def_readonly("m4", &SpectralMoments::m4, "(m4x + m4y)/2")
      .def_readonly("m2x", &SpectralMoments::m2x, "m2 of profiles along x [-]")
      .def_readonly("m2y", &SpectralMoments::m2y, "m2 of profiles along y [-]")
      .def_readonly("m4x", &SpectralMoments::m4x, "m4 of profiles along x [1/m²]")
      .def_readonly("m4y", &SpectralMoments::m4y, "m4 of profiles along y [1/m²]")
      .def_property_readonly("bandwidth", &SpectralMoments::bandwidth, "α [-]");
  py::class_<NayakEstimates>(m, "NayakEstimates",
                             "Nayak/McCool summit statistics (η, β, σ_s) of an isotropic "
                             "Gaussian surface from its spectral moments")
      .def_readonly("sampling_interval", &NayakEstimates::sampling_interval, "h the moments were computed at [m] (max of h_x, h_y)")
      .def_readonly("summit_density", &NayakEstimates::summit_density, "η = m4/(6π√3 m2) [1/m²]")
      .def_readonly("summit_radius", &NayakEstimates::summit_radius, "β = 0.375 √(π/m4) [m]")
      .def_readonly("summit_height_std", &NayakEstimates::summit_height_std, "σ_s = √(1 - 0.8968/α) σ [m] (NaN if α < 0.8968)")
      .def_readonly("bandwidth", &NayakEstimates::bandwidth, "α [-]")
      .def_readonly("moments", &NayakEstimates::moments, "the moments the estimates come from");
  m.def("finite_difference_moments", &finite_difference_moments, py::arg("surface"),
        "SpectralMoments from finite differences of the samples (masks respected): the moments "
        "the sampled surface has at its spacing");
  m.def("psd_moments", &psd_moments, py::arg("surface"), py::arg("window") = Window::hann,
        "SpectralMoments from the 2D periodogram (complete grids only: ValueError for missing "
        "points)");
  m.def("nayak_estimates", &nayak_estimates, py::arg("moments"), py::arg("sampling_interval"),
        "NayakEstimates (η [1/m²], β [m], σ_s [m]) from SpectralMoments; sampling_interval [m] is "
        "recorded with them");
  m.def("power_spectrum_2d",
        [](const Surface& s, Window w)
        {
          const PowerSpectrum2D p = power_spectrum_2d(s, w);
          return py::make_tuple(to_array(p.psd), vector_array(p.qx), vector_array(p.qy));
        },
        py::arg("surface"), py::arg("window") = Window::hann,
        "(C [m^4] in DFT order, q_x [rad/m], q_y [rad/m]); Σ C Δq_x Δq_y = mean z²");
  m.def("radial_spectrum",
        [](const Surface& s, Window w)
        {
          const RadialSpectrum r = radial_average(power_spectrum_2d(s, w));
          return py::make_tuple(vector_array(r.q), vector_array(r.psd), vector_array(r.count));
        },
        py::arg("surface"), py::arg("window") = Window::hann,
        "(q [rad/m], C [m^4], mode count) radially averaged");
  py::class_<HurstFit>(m, "HurstFit")
      .def_readonly("hurst_exponent", &HurstFit::hurst_exponent, "H = -slope/2 - 1")
      .def_readonly("slope", &HurstFit::slope, "d ln C / d ln q")
      .def_readonly("slope_std_error", &HurstFit::slope_std_error, "from the weighted residuals")
      .def_readonly("log_prefactor", &HurstFit::log_prefactor, "ln C at q = 1 rad/m")
      .def_readonly("q_min", &HurstFit::q_min, "lower end of the band used [rad/m]")
      .def_readonly("q_max", &HurstFit::q_max, "upper end of the band used [rad/m]")
      .def_readonly("bins", &HurstFit::bins, "bins used");
  m.def("fit_hurst_exponent",
        [](const DoubleArray& q, const DoubleArray& c, const py::array_t<std::int64_t>& n,
           double q_min, double q_max)
        {
          if (q.size() != c.size() || q.size() != n.size())
            throw py::value_error("fit_hurst_exponent: q, psd and count differ in length");
          RadialSpectrum r;
          r.q.assign(q.data(), q.data() + q.size());
          r.psd.assign(c.data(), c.data() + c.size());
          r.count.assign(n.data(), n.data() + n.size());
          return fit_hurst_exponent(r, q_min, q_max);
        },
        py::arg("q"), py::arg("psd"), py::arg("count"), py::arg("q_min"), py::arg("q_max"));

  // ---- overlap, parameters, resampling ---------------------------------------------------
  py::class_<ApertureDistribution>(m, "ApertureDistribution",
                                   "fraction{e <= Δ} of an aperture field (theory §3)")
      .def(py::init<const Surface&>(), py::arg("aperture"))
      .def("overlap_ratio",
           [](const ApertureDistribution& d, const DoubleArray& closure) -> py::object
           {
             DoubleArray out = empty_like(closure);
             d.overlap_ratio(as_span(closure), {out.mutable_data(), std::size_t(out.size())});
             if (closure.ndim() == 0)
               return out.attr("item")();
             return out;
           },
           py::arg("closure"), "fraction{e <= Δ} [-] at closure Δ [m]");
  m.def("asperity_parameters",
        py::overload_cast<const SummitStatistics&, double>(&asperity_parameters),
        py::arg("statistics"), py::arg("composite_modulus"),
        "AsperityParameters from counted statistics (at least 2 summits) and E* [Pa]");
  m.def("asperity_parameters",
        py::overload_cast<const NayakEstimates&, double>(&asperity_parameters),
        py::arg("estimates"), py::arg("composite_modulus"),
        "AsperityParameters from the spectral (Nayak/McCool) estimates and E* [Pa]");
  py::class_<ResamplingRow>(m, "ResamplingRow")
      .def_readonly("factor", &ResamplingRow::factor, "the surface sampled every `factor`-th point")
      .def_readonly("sampling_interval", &ResamplingRow::sampling_interval, "h·factor [m] (max of the two directions)")
      .def_readonly("summits", &ResamplingRow::summits, "counted statistics at this h")
      .def_readonly("spectral", &ResamplingRow::spectral, "finite-difference Nayak/McCool estimates at this h");
  m.def("resampling_study", &resampling_study, py::arg("surface"), py::arg("factors"));
}

} // namespace rockjoint::python

