// SPDX-License-Identifier: MIT
#include "fft2.hpp"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_fft_complex.h>

#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

namespace rockjoint::topography
{

namespace
{
/// One GSL mixed-radix plan (wavetable + workspace) for length n.
class Plan
{
public:
  explicit Plan(std::size_t n)
      : _n(n), _table(gsl_fft_complex_wavetable_alloc(n)), _work(gsl_fft_complex_workspace_alloc(n))
  {
    if (!_table || !_work)
      throw std::runtime_error("fft2: cannot allocate a GSL FFT plan of length "
                               + std::to_string(n));
  }
  ~Plan()
  {
    gsl_fft_complex_wavetable_free(_table);
    gsl_fft_complex_workspace_free(_work);
  }
  Plan(const Plan&) = delete;
  Plan& operator=(const Plan&) = delete;

  void run(std::complex<double>* data, bool inverse) const
  {
    auto* d = reinterpret_cast<double*>(data);
    const int status = inverse ? gsl_fft_complex_backward(d, 1, _n, _table, _work)
                               : gsl_fft_complex_forward(d, 1, _n, _table, _work);
    if (status != GSL_SUCCESS)
      throw std::runtime_error(std::string("fft2: GSL FFT failed: ") + gsl_strerror(status));
  }

private:
  std::size_t _n;
  gsl_fft_complex_wavetable* _table;
  gsl_fft_complex_workspace* _work;
};
} // namespace

void fft2(ComplexGrid& data, bool inverse)
{
  gsl_set_error_handler_off(); // codes become exceptions here, never abort()
  const Eigen::Index rows = data.rows(), cols = data.cols();
  if (rows == 0 || cols == 0)
    return;
  if (cols > 1)
  {
    Plan plan(cols);
    for (Eigen::Index i = 0; i < rows; ++i)
      plan.run(data.data() + i * cols, inverse); // rows are contiguous (row-major)
  }
  if (rows > 1)
  {
    Plan plan(rows);
    std::vector<std::complex<double>> column(rows);
    for (Eigen::Index j = 0; j < cols; ++j)
    {
      for (Eigen::Index i = 0; i < rows; ++i)
        column[i] = data(i, j);
      plan.run(column.data(), inverse);
      for (Eigen::Index i = 0; i < rows; ++i)
        data(i, j) = column[i];
    }
  }
  if (inverse)
    data /= static_cast<double>(rows * cols);
}

double angular_frequency(Eigen::Index k, Eigen::Index n, double spacing)
{
  const Eigen::Index signed_k = (k <= (n - 1) / 2) ? k : k - n;
  return 2.0 * std::numbers::pi * static_cast<double>(signed_k)
         / (static_cast<double>(n) * spacing);
}

} // namespace rockjoint::topography
