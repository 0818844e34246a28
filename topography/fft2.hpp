// SPDX-License-Identifier: MIT
#pragma once
/// @file fft2.hpp
/// Two-dimensional discrete Fourier transform (GSL mixed-radix, any size) for the
/// Fourier-filtering synthesis and the power spectrum.

#include <Eigen/Core>

#include <complex>

namespace rockjoint::topography
{

/// A row-major grid of complex values (the DFT of a HeightGrid).
using ComplexGrid
    = Eigen::Array<std::complex<double>, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

/// In-place 2D DFT. Forward: Z_k = Σ_n z_n e^{-2πi k·n/N} (unnormalised); inverse: with
/// e^{+2πi...} and divided by rows·cols, so inverse(forward(z)) = z.
void fft2(ComplexGrid& data, bool inverse = false);

/// Signed angular frequency of DFT index k of an n-point transform with step h [m]:
/// q = 2π k/(n h) for k < n/2 (rounded up), else 2π (k - n)/(n h)  [rad/m].
double angular_frequency(Eigen::Index k, Eigen::Index n, double spacing);

} // namespace rockjoint::topography
