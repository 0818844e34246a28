// SPDX-License-Identifier: MIT
#include "equivalent_continuum.hpp"

#include <rockjoint/constitutive/validation.hpp>
#include <rockjoint/joint/joint_frame.hpp>
#include <rockjoint/joint/joint_slip.hpp>

#include <Eigen/Dense>

#include <cmath>
#include <functional>
#include <limits>
#include <stdexcept>

namespace rockjoint::continuum
{
namespace
{
using Matrix = Eigen::MatrixXd;
using Vector = Eigen::VectorXd;
using Frame = joint::JointFrame;

/// Frame (n, t1[, t2]) of a set: the discrete joint element's rule (joint::joint_frame with its
/// default reference e_x), so a smeared set's shear axes are its discrete joints'.
Frame set_frame(int gdim, const std::array<double, 3>& n) { return joint::joint_frame(gdim, n); }

/// P(n): Voigt vector of sym(n ⊗ g) (engineering shear) as a matrix acting on g (gdim). Its
/// transpose maps the Voigt stress to the traction σ n (virtual work: σ : sym(n ⊗ g) = σn · g).
Matrix voigt_dyad(int gdim, const std::array<double, 3>& n)
{
  if (gdim == 2)
  {
    Matrix p(3, 2);
    p << n[0], 0.0, 0.0, n[1], n[1], n[0];
    return p;
  }
  Matrix p(6, 3);
  p << n[0], 0.0, 0.0, //
      0.0, n[1], 0.0,  //
      0.0, 0.0, n[2],  //
      0.0, n[2], n[1], //
      n[2], 0.0, n[0], //
      n[1], n[0], 0.0;
  return p;
}

/// B_k = (1/s_k) P(n_k) Q_kᵀ: crack strain per unit local jump of set k.
Matrix crack_strain_operator(int gdim, const JointSet& set, const Frame& q)
{
  Matrix qt(gdim, gdim);
  for (int a = 0; a < gdim; ++a)
    for (int i = 0; i < gdim; ++i)
      qt(i, a) = q[a][i];
  return voigt_dyad(gdim, set.normal) * qt / set.spacing;
}

Matrix stiffness_matrix(int gdim, double young, double poisson)
{
  const double lambda = young * poisson / ((1.0 + poisson) * (1.0 - 2.0 * poisson));
  const double mu = young / (2.0 * (1.0 + poisson));
  const int nv = gdim == 2 ? 3 : 6;
  Matrix d = Matrix::Zero(nv, nv);
  for (int i = 0; i < gdim; ++i)
  {
    for (int j = 0; j < gdim; ++j)
      d(i, j) = lambda;
    d(i, i) += 2.0 * mu;
  }
  for (int i = gdim; i < nv; ++i)
    d(i, i) = mu;
  return d;
}

/// One linearisation of a local problem: residual r and matrix A such that the Newton step
/// is Δj = A⁻¹ r; `finite` false if the joint law returned a non-finite traction (a jump
/// past the maximum closure).
struct Linearisation
{
  Vector residual;
  Matrix matrix;
  bool finite = true;
};

struct NewtonResult
{
  Vector jump;
  int iterations = 0;
  bool converged = false;
};

/// Damped Newton on the stacked jumps: full step, halved (at most 40 times) until the traction
/// is finite and |r| decreases (the joint laws are semismooth at Δ = 0, the strength and the
/// cut-off; the halving keeps closures below a law's maximum closure). A is solved by a
/// complete orthogonal decomposition: with open sets of zero residual stiffness A is singular
/// and the minimum-norm step leaves the indeterminate jump where it is.
/// Converged when |r| <= 1e-10 scale or the step is below 1e-13 (|j| + 1e-18 m).
NewtonResult damped_newton(const std::function<Linearisation(const Vector&)>& linearise,
                           Vector jump, double scale)
{
  NewtonResult out;
  Linearisation lin = linearise(jump);
  if (!lin.finite)
    return out;
  constexpr int max_iterations = 60;
  for (int it = 0; it < max_iterations; ++it)
  {
    const double norm = lin.residual.norm();
    if (norm <= 1e-10 * scale)
    {
      out.jump = jump;
      out.converged = true;
      return out;
    }
    const Vector step = lin.matrix.completeOrthogonalDecomposition().solve(lin.residual);
    if (!step.allFinite())
      return out;
    double alpha = 1.0;
    bool accepted = false;
    for (int cut = 0; cut < 40; ++cut, alpha *= 0.5)
    {
      const Vector candidate = jump + alpha * step;
      Linearisation next = linearise(candidate);
      if (next.finite && next.residual.norm() < (1.0 - 1e-4 * alpha) * norm)
      {
        jump = candidate;
        lin = std::move(next);
        accepted = true;
        break;
      }
    }
    out.iterations = it + 1;
    if (!accepted || step.norm() <= 1e-13 * (jump.norm() + 1e-18))
    {
      // No decrease possible: converged only if the step is at round-off of the jump.
      out.converged = step.norm() <= 1e-13 * (jump.norm() + 1e-18)
                      || lin.residual.norm() <= 1e-10 * scale;
      out.jump = jump;
      return out;
    }
  }
  out.converged = lin.residual.norm() <= 1e-10 * scale;
  out.jump = jump;
  return out;
}

Vector to_vector(std::span<const double> x)
{
  return Eigen::Map<const Vector>(x.data(), static_cast<Eigen::Index>(x.size()));
}
} // namespace

EquivalentContinuum::EquivalentContinuum(int gdim, double young, double poisson,
                                         std::vector<JointSet> sets)
    : _gdim(gdim), _young(young), _poisson(poisson), _sets(std::move(sets))
{
  namespace v = constitutive::validation;
  const std::string owner = "EquivalentContinuum";
  if (gdim != 2 && gdim != 3)
    v::fail(owner, "gdim", gdim, "", "2 (plane strain) or 3");
  v::positive(owner, "young", young, "Pa");
  v::in_range(owner, "poisson", poisson, "-", -1.0, 0.5);
  for (const JointSet& set : _sets)
  {
    const std::string label = owner + " joint set '" + set.label + "'";
    v::positive(label, "spacing", set.spacing, "m");
    const auto& n = set.normal;
    for (int i = 0; i < 3; ++i)
      v::finite(label, "normal[" + std::to_string(i) + "]", n[i], "-");
    if (gdim == 2 && n[2] != 0.0)
      v::fail(label, "normal[2]", n[2], "-", "0 in 2D (the set's normal lies in the plane)");
    const double length = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    if (std::abs(length - 1.0) > 1e-8)
      v::fail(label, "|normal|", length, "-", "1 (a unit normal, to 1e-8)");
    joint::validate(set.behaviour, set.label);
    _frames.push_back(set_frame(gdim, n));
  }
}

std::vector<double> EquivalentContinuum::rock_stiffness() const
{
  const Matrix d = stiffness_matrix(_gdim, _young, _poisson);
  std::vector<double> out(static_cast<std::size_t>(d.size()));
  Eigen::Map<Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(
      out.data(), d.rows(), d.cols())
      = d;
  return out;
}

PointResponse EquivalentContinuum::evaluate(std::span<const double> strain,
                                            std::span<const SetState> converged,
                                            std::span<SetState> trial) const
{
  const int nv = strain_size();
  const int d = _gdim;
  const std::size_t ns = _sets.size();
  if (strain.size() != static_cast<std::size_t>(nv))
    throw std::invalid_argument("EquivalentContinuum::evaluate: strain has "
                                + std::to_string(strain.size()) + " components; expected "
                                + std::to_string(nv));
  if (converged.size() != ns || trial.size() != ns)
    throw std::invalid_argument("EquivalentContinuum::evaluate: " + std::to_string(ns)
                                + " set states expected (converged and trial)");
  for (int i = 0; i < nv; ++i)
    constitutive::validation::finite("EquivalentContinuum::evaluate", "strain[" + std::to_string(i) + "]",
                                     strain[i], "-");

  const Matrix dmat = stiffness_matrix(d, _young, _poisson);
  const Vector eps = to_vector(strain);
  const Eigen::Index m = static_cast<Eigen::Index>(ns) * d;
  Matrix b(nv, m);
  for (std::size_t k = 0; k < ns; ++k)
    b.middleCols(static_cast<Eigen::Index>(k) * d, d) = crack_strain_operator(d, _sets[k], _frames[k]);
  const Matrix btdb = b.transpose() * dmat * b;

  PointResponse out;
  // r_k = B_kᵀ σ - t_k / s_k, A = Bᵀ D B + diag(T_k / s_k): the Newton step is A⁻¹ r.
  auto linearise = [&](const Vector& jump)
  {
    Linearisation lin;
    const Vector sigma = dmat * (eps - b * jump);
    lin.residual = b.transpose() * sigma;
    lin.matrix = btdb;
    for (std::size_t k = 0; k < ns; ++k)
    {
      const Eigen::Index o = static_cast<Eigen::Index>(k) * d;
      std::array<double, 3> j{};
      for (int a = 0; a < d; ++a)
        j[a] = jump(o + a);
      const joint::LocalResponse r
          = joint::joint_response(_sets[k].behaviour, d, j, converged[k].joint, trial[k].joint);
      const double s = _sets[k].spacing;
      for (int a = 0; a < d; ++a)
      {
        if (!std::isfinite(r.traction[a]))
          lin.finite = false;
        lin.residual(o + a) -= r.traction[a] / s;
        for (int c = 0; c < d; ++c)
          lin.matrix(o + a, o + c) += r.tangent[a][c] / s;
      }
    }
    lin.finite = lin.finite && lin.residual.allFinite() && lin.matrix.allFinite();
    return lin;
  };

  Vector start(m), previous(m);
  for (std::size_t k = 0; k < ns; ++k)
    for (int a = 0; a < d; ++a)
    {
      start(static_cast<Eigen::Index>(k) * d + a) = converged[k].jump[a];
      previous(static_cast<Eigen::Index>(k) * d + a) = trial[k].jump[a];
    }
  const double scale = (b.transpose() * dmat * eps).norm() + btdb.norm() * start.norm()
                       + std::numeric_limits<double>::min();
  NewtonResult solved = ns == 0 ? NewtonResult{Vector(0), 0, true}
                                : damped_newton(linearise, start, scale);
  // A failed solve from the converged jumps is retried from the last trial jumps (the
  // previous global iterate's, close to the solution once the global Newton has made progress):
  // the local problem is semismooth (stick/slip/open kinks), and with sets open or sliding it is
  // held only by the residual stiffness, so a start far from the solution can stall at a kink.
  // On the tunnel bench (s = 1 m) this took the smeared model from 326 to 61 Newton iterations.
  if (!solved.converged && previous.allFinite() && previous != start)
  {
    NewtonResult second = damped_newton(linearise, previous, scale);
    second.iterations += solved.iterations;
    solved = second;
  }
  out.iterations = solved.iterations;
  out.converged = solved.converged;
  if (!solved.converged)
  {
    out.stress.fill(std::numeric_limits<double>::quiet_NaN());
    out.tangent.fill(std::numeric_limits<double>::quiet_NaN());
    return out;
  }
  // Final linearisation at the solution: the trial states and the local Jacobian A.
  const Linearisation lin = ns == 0 ? Linearisation{Vector(0), Matrix(0, 0), true}
                                    : linearise(solved.jump);
  for (std::size_t k = 0; k < ns; ++k)
    for (int a = 0; a < 3; ++a)
      trial[k].jump[a] = a < d ? solved.jump(static_cast<Eigen::Index>(k) * d + a) : 0.0;
  const Vector sigma = dmat * (eps - b * solved.jump);
  // Static condensation: dj/dε = A⁻¹ Bᵀ D, so C = D - D B A⁻¹ Bᵀ D (A⁻¹ the minimum-norm
  // solve, exact where A is regular; see damped_newton for the singular open case).
  Matrix tangent = dmat;
  if (ns > 0)
    tangent -= dmat * b * lin.matrix.completeOrthogonalDecomposition().solve(b.transpose() * dmat);
  for (int i = 0; i < nv; ++i)
  {
    out.stress[i] = sigma(i);
    for (int j = 0; j < nv; ++j)
      out.tangent[i * nv + j] = tangent(i, j);
  }
  return out;
}

std::vector<double> EquivalentContinuum::strain_at_stress(std::span<const double> stress,
                                                          std::span<SetState> states) const
{
  const int nv = strain_size();
  const int d = _gdim;
  if (stress.size() != static_cast<std::size_t>(nv) || states.size() != _sets.size())
    throw std::invalid_argument("EquivalentContinuum::strain_at_stress: expected "
                                + std::to_string(nv) + " stress components and "
                                + std::to_string(_sets.size()) + " set states");
  for (int i = 0; i < nv; ++i)
    constitutive::validation::finite("EquivalentContinuum::strain_at_stress",
                                     "stress[" + std::to_string(i) + "]", stress[i], "Pa");
  const Vector sigma = to_vector(stress);
  const Matrix dmat = stiffness_matrix(d, _young, _poisson);
  Vector eps = dmat.partialPivLu().solve(sigma);
  for (std::size_t k = 0; k < _sets.size(); ++k)
  {
    const Matrix bk = crack_strain_operator(d, _sets[k], _frames[k]);
    const Vector target = _sets[k].spacing * bk.transpose() * sigma; // Q_k σ n_k
    const joint::JointPointState virgin{};
    auto linearise = [&](const Vector& jump)
    {
      std::array<double, 3> j{};
      for (int a = 0; a < d; ++a)
        j[a] = jump(a);
      const joint::LocalResponse r
          = joint::joint_response(_sets[k].behaviour, d, j, virgin, states[k].joint);
      Linearisation lin{target, Matrix(d, d), true};
      for (int a = 0; a < d; ++a)
      {
        lin.residual(a) -= r.traction[a];
        for (int c = 0; c < d; ++c)
          lin.matrix(a, c) = r.tangent[a][c];
      }
      lin.finite = lin.residual.allFinite() && lin.matrix.allFinite();
      return lin;
    };
    const NewtonResult solved
        = damped_newton(linearise, Vector::Zero(d), target.norm() + std::numeric_limits<double>::min());
    if (!solved.converged)
      throw std::domain_error("EquivalentContinuum::strain_at_stress: joint set '" + _sets[k].label
                              + "' cannot carry the traction of the given stress (tension on an "
                                "open joint, or shear beyond its strength)");
    linearise(solved.jump); // trial state at the solution
    for (int a = 0; a < 3; ++a)
      states[k].jump[a] = a < d ? solved.jump(a) : 0.0;
    eps += bk * solved.jump;
  }
  return std::vector<double>(eps.data(), eps.data() + eps.size());
}

std::size_t evaluate_points(const EquivalentContinuum& material, std::span<const double> strain,
                            std::span<const SetState> converged, std::span<SetState> trial,
                            std::span<double> stress, std::span<double> tangent)
{
  const std::size_t nv = static_cast<std::size_t>(material.strain_size());
  const std::size_t ns = material.num_sets();
  const std::size_t n = strain.size() / nv;
  if (strain.size() != n * nv || converged.size() != n * ns || trial.size() != n * ns
      || stress.size() != n * nv || tangent.size() != n * nv * nv)
    throw std::invalid_argument("evaluate_points: inconsistent sizes for "
                                + std::to_string(n) + " points of " + std::to_string(nv)
                                + " strain components and " + std::to_string(ns) + " sets");
  std::size_t failed = 0;
  for (std::size_t p = 0; p < n; ++p)
  {
    for (std::size_t i = 0; i < nv; ++i)
      if (!std::isfinite(strain[p * nv + i]))
        throw std::invalid_argument("evaluate_points: strain of point " + std::to_string(p)
                                    + ", component " + std::to_string(i) + " is "
                                    + std::to_string(strain[p * nv + i]) + "; it must be finite");
    const PointResponse r = material.evaluate(strain.subspan(p * nv, nv),
                                              converged.subspan(p * ns, ns),
                                              trial.subspan(p * ns, ns));
    failed += r.converged ? 0 : 1;
    std::copy_n(r.stress.begin(), nv, stress.begin() + static_cast<std::ptrdiff_t>(p * nv));
    std::copy_n(r.tangent.begin(), nv * nv,
                tangent.begin() + static_cast<std::ptrdiff_t>(p * nv * nv));
  }
  return failed;
}

} // namespace rockjoint::continuum
