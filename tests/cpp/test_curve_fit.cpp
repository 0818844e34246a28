// SPDX-License-Identifier: MIT
// Levenberg-Marquardt curve fit (constitutive/curve_fit.hpp). References are closed forms:
// weighted linear regression (normal equations written out here) for the parameters and the
// covariance s²(XᵀWX)⁻¹, and exact recovery of a nonlinear model from noise-free data.
#include <rockjoint/constitutive/curve_fit.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "expect_error.hpp"

using namespace rockjoint::constitutive::calibration;

using rockjoint::testing::expect_error;

TEST(CurveFit, WeightedStraightLineMatchesTheNormalEquations)
{
  // y = a + b x with deterministic scatter; the weighted LS solution and its covariance
  // C = s² (XᵀWX)⁻¹, s² = χ²/(N-2), in closed form.
  const int n = 12;
  std::vector<double> x(n), y(n), w(n);
  for (int i = 0; i < n; ++i)
  {
    x[i] = 0.5 * i;
    y[i] = 1.5 - 0.75 * x[i] + 0.05 * std::sin(3.0 * i + 1.0);
    w[i] = 1.0 + 0.25 * (i % 3);
  }
  double sw = 0, swx = 0, swxx = 0, swy = 0, swxy = 0;
  for (int i = 0; i < n; ++i)
  {
    sw += w[i];
    swx += w[i] * x[i];
    swxx += w[i] * x[i] * x[i];
    swy += w[i] * y[i];
    swxy += w[i] * x[i] * y[i];
  }
  const double det = sw * swxx - swx * swx;
  const double a = (swxx * swy - swx * swxy) / det, b = (sw * swxy - swx * swy) / det;
  double chi2 = 0;
  for (int i = 0; i < n; ++i)
    chi2 += w[i] * std::pow(a + b * x[i] - y[i], 2);
  const double s2 = chi2 / (n - 2);
  const double caa = s2 * swxx / det, cbb = s2 * sw / det, cab = -s2 * swx / det;

  auto line = [&](std::span<const double> p, std::span<double> m)
  {
    for (int i = 0; i < n; ++i)
      m[i] = p[0] + p[1] * x[i];
  };
  const std::vector<double> start{0.0, 0.0};
  const CurveFitResult r = fit_curve(line, y, start, w);
  EXPECT_TRUE(r.converged) << r.message;
  EXPECT_NEAR(r.parameters[0], a, 1e-9);
  EXPECT_NEAR(r.parameters[1], b, 1e-9);
  EXPECT_NEAR(r.chi_squared, chi2, 1e-9 * chi2);
  EXPECT_EQ(r.degrees_of_freedom, n - 2);
  // The forward-difference Jacobian of a linear model is exact up to rounding.
  EXPECT_NEAR(r.covariance[0], caa, 1e-6 * caa);
  EXPECT_NEAR(r.covariance[3], cbb, 1e-6 * cbb);
  EXPECT_NEAR(r.covariance[1], cab, 1e-6 * std::abs(cab));
  EXPECT_NEAR(r.standard_errors[1], std::sqrt(cbb), 1e-6 * std::sqrt(cbb));
  for (int i = 0; i < n; ++i)
    EXPECT_NEAR(r.residuals[i], a + b * x[i] - y[i], 1e-9);
}

TEST(CurveFit, RecoversANonlinearModelFromExactData)
{
  // y = A (1 - exp(-x/τ)) (the shape of the exponential closure law), parameters in log form.
  const double A = 0.3, tau = 4.0;
  std::vector<double> x, y;
  for (double s = 0.25; s <= 20.0; s *= 1.3)
  {
    x.push_back(s);
    y.push_back(A * -std::expm1(-s / tau));
  }
  auto model = [&](std::span<const double> p, std::span<double> m)
  {
    for (std::size_t i = 0; i < x.size(); ++i)
      m[i] = std::exp(p[0]) * -std::expm1(-x[i] / std::exp(p[1]));
  };
  const std::vector<double> start{std::log(1.0), std::log(1.0)};
  const CurveFitResult r = fit_curve(model, y, start);
  EXPECT_TRUE(r.converged) << r.message;
  EXPECT_NEAR(std::exp(r.parameters[0]), A, 1e-10 * A);
  EXPECT_NEAR(std::exp(r.parameters[1]), tau, 1e-10 * tau);
  EXPECT_LT(r.chi_squared, 1e-24);
  EXPECT_GT(r.iterations, 0);
}

TEST(CurveFit, AParameterTheModelIgnoresHasAnUnboundedUncertainty)
{
  // y = a + 0 * b: the data say nothing about b (its Jacobian column is zero), so its standard
  // error is +inf, not the 0 GSL leaves in its covariance row; a = mean(y) keeps s / sqrt(N).
  const std::vector<double> y{1.0, 1.2, 0.9, 1.1, 0.8};
  auto model = [](std::span<const double> p, std::span<double> m)
  {
    for (double& v : m)
      v = p[0] + 0.0 * p[1];
  };
  const CurveFitResult r = fit_curve(model, y, std::vector<double>{0.0, 3.0});
  EXPECT_NEAR(r.parameters[0], 1.0, 1e-10);
  EXPECT_TRUE(std::isinf(r.standard_errors[1]));
  // s² = Σ(y - ȳ)² / (N - P) = 0.1 / 3, σ_a = s / √N
  EXPECT_NEAR(r.standard_errors[0], std::sqrt(0.1 / 3.0 / 5.0), 1e-8);
}

TEST(CurveFit, ModelExceptionsAreRethrownAndBadInputNamed)
{
  const std::vector<double> y{1, 2, 3}, p{0.0};
  auto throwing = [](std::span<const double>, std::span<double>)
  { throw std::domain_error("model outside its domain"); };
  EXPECT_THROW(fit_curve(throwing, y, p), std::domain_error);
  auto constant = [](std::span<const double> q, std::span<double> m)
  {
    for (double& v : m)
      v = q[0];
  };
  const double nan = std::numeric_limits<double>::quiet_NaN();
  expect_error([&] { fit_curve(constant, std::vector<double>{1.0}, p); }, "more observations");
  expect_error([&] { fit_curve(constant, std::vector<double>{1, nan, 3}, p); }, "observed[1]");
  expect_error([&] { fit_curve(constant, y, std::vector<double>{nan}); }, "initial[0]");
  expect_error([&] { fit_curve(constant, y, p, std::vector<double>{1, 1}); }, "weights");
  expect_error([&] { fit_curve(constant, y, p, std::vector<double>{1, -1, 1}); }, "negative");
  expect_error([&] { fit_curve(constant, y, p, std::vector<double>{0, 0, 0}); }, "all weights");
  auto not_finite = [](std::span<const double>, std::span<double> m)
  {
    for (double& v : m)
      v = std::numeric_limits<double>::infinity();
  };
  expect_error([&] { fit_curve(not_finite, y, p); }, "not finite");
  // The mean of the data, with its standard error s/√N.
  const CurveFitResult r = fit_curve(constant, y, p);
  EXPECT_NEAR(r.parameters[0], 2.0, 1e-10);
  EXPECT_NEAR(r.standard_errors[0], std::sqrt(1.0 / 3.0), 1e-6);
}
