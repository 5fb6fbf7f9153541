// punch/src/toeplitz_product.hpp: products with a Toeplitz matrix by FFT (internal to punch/src).
//
// WHAT IT COMPUTES. y = T v for the n x n matrix T(i, j) = t[j - i + n - 1] (t: its 2n - 1
// diagonals, the action of panel j at the collocation point i of a uniform boundary-element
// grid), and the same product restricted to a subset of rows and columns (the active panels of a
// contact search: zero outside the columns, read at the rows). T is embedded in a circulant of
// size M >= 2n - 1 (a power of two), whose product is a cyclic convolution: y = ifft(fft(c) .*
// fft(v)) with c[k] = t[n - 1 - k] (k = i - j >= 0) and c[M - k] = t[n - 1 + k] (k = j - i > 0).
// A matrix that is itself circulant (a periodic grid: t[n - 1 + k] = t[k - 1] for k > 0) is taken
// as it is, M = n, when n is a multiple of 4 whose other prime factors are 2, 3 and 5 (fast
// radices): about a third of the padded work at n = 1e5 2^k. The transforms are real (half
// spectra), by FFTW (Debian's libfftw3: plans FFTW_ESTIMATE, made once per object). WHY FFTW and
// not Eigen's default kissfft: a product of length 2^21 (the coarse search's finest grid on a
// 1e5-sample profile) took 51-60 ms instead of 180 ms, one of 800000 9-10.5 ms instead of 52 ms
// (measured, one core, a forward and an inverse real transform); the ~980-patch periodic
// profile's coarse solve took 42 s with kissfft, 29 s of it on the grid of 2^21 panels (traced).
// O(M log M) a product instead of O(n^2); memory O(M).
//
// ACCURACY. The FFT's rounding: |y - T v| <~ eps log2(M) max|t| sum|v|. Near that floor a
// product is no longer exact where y is small against the data; the contact search compares
// penetrations with 1e-9 of the profile's span, far above it.
//
// Thread safety: FFTW's planner is not thread-safe, so plans are made and destroyed under one
// mutex (planner_mutex); executing them is. One object must not be used by two threads at once
// (its work arrays are members).
#pragma once

#include <Eigen/Dense>
#include <fftw3.h>

#include <algorithm>
#include <complex>
#include <cstddef>
#include <mutex>
#include <new>
#include <vector>

namespace rhabel::punch::detail {

class toeplitz_product {
 public:
  /// t: the 2n - 1 diagonals, t[j - i + n - 1] = T(i, j); circulant: T is (see the top of the file).
  toeplitz_product(const std::vector<double>& t, std::size_t n, bool circulant = false) : n_(n) {
    if (circulant && fast_length(n_)) {
      size_ = n_;
    } else {
      size_ = 1;
      while (size_ < 2 * n_) size_ *= 2;
    }
    real_ = fftw_alloc_real(size_);
    spectrum_ = fftw_alloc_complex(size_ / 2 + 1);
    if (!real_ || !spectrum_) {
      release();
      throw std::bad_alloc();
    }
    {
      const std::lock_guard<std::mutex> lock(planner_mutex());
      const int m = static_cast<int>(size_);
      forward_ = fftw_plan_dft_r2c_1d(m, real_, spectrum_, FFTW_ESTIMATE);
      backward_ = fftw_plan_dft_c2r_1d(m, spectrum_, real_, FFTW_ESTIMATE);
    }
    if (!forward_ || !backward_) {
      release();
      throw std::bad_alloc();
    }
    // The circulant's first column c (see the top), transformed; 1/M folds in the inverse's scale
    // (FFTW's transforms are unnormalised).
    std::fill(real_, real_ + size_, 0.0);
    for (std::size_t k = 0; k < n_; ++k) real_[k] = t[n_ - 1 - k];
    if (size_ != n_)
      for (std::size_t k = 1; k < n_; ++k) real_[size_ - k] = t[n_ - 1 + k];
    fftw_execute(forward_);
    hat_.resize(size_ / 2 + 1);
    const double scale = 1.0 / static_cast<double>(size_);
    for (std::size_t k = 0; k < hat_.size(); ++k) hat_[k] = scale * std::complex<double>(spectrum_[k][0], spectrum_[k][1]);
  }
  ~toeplitz_product() { release(); }
  toeplitz_product(const toeplitz_product&) = delete;
  toeplitz_product& operator=(const toeplitz_product&) = delete;

  /// The transform's length (2^k >= 2n, or n for a circulant of a fast length).
  std::size_t transform_length() const { return size_; }

  std::size_t size() const { return n_; }

  /// T v, v of length n.
  Eigen::VectorXd apply(const Eigen::VectorXd& v) {
    std::fill(real_, real_ + size_, 0.0);
    for (std::size_t j = 0; j < n_; ++j) real_[j] = v[static_cast<Eigen::Index>(j)];
    return convolve();
  }

  /// (T restricted to the columns `columns`) v, v of length columns.size(): all n rows.
  Eigen::VectorXd apply(const std::vector<std::size_t>& columns, const Eigen::VectorXd& v) {
    std::fill(real_, real_ + size_, 0.0);
    for (std::size_t c = 0; c < columns.size(); ++c) real_[columns[c]] = v[static_cast<Eigen::Index>(c)];
    return convolve();
  }

  /// (T restricted to the rows `rows` and the columns `columns`) v, v of length columns.size().
  Eigen::VectorXd apply(const std::vector<std::size_t>& rows, const std::vector<std::size_t>& columns,
                        const Eigen::VectorXd& v) {
    const Eigen::VectorXd full = apply(columns, v);
    Eigen::VectorXd out(static_cast<Eigen::Index>(rows.size()));
    for (std::size_t r = 0; r < rows.size(); ++r) out[static_cast<Eigen::Index>(r)] = full[static_cast<Eigen::Index>(rows[r])];
    return out;
  }

 private:
  /// A multiple of 4 whose other prime factors are 2, 3 and 5.
  static bool fast_length(std::size_t n) {
    if (n == 0 || n % 4 != 0) return false;
    for (std::size_t p : {2, 3, 5})
      while (n % p == 0) n /= p;
    return n == 1;
  }

  /// The one mutex of FFTW's planner (every object's plans, on any thread).
  static std::mutex& planner_mutex() {
    static std::mutex m;
    return m;
  }

  void release() {
    {
      const std::lock_guard<std::mutex> lock(planner_mutex());
      if (forward_) fftw_destroy_plan(forward_);
      if (backward_) fftw_destroy_plan(backward_);
    }
    forward_ = backward_ = nullptr;
    if (real_) fftw_free(real_);
    if (spectrum_) fftw_free(spectrum_);
    real_ = nullptr;
    spectrum_ = nullptr;
  }

  /// The cyclic convolution of real_ (the padded v) with c: real_ -> its spectrum, times hat_,
  /// back into real_; the first n values.
  Eigen::VectorXd convolve() {
    fftw_execute(forward_);
    for (std::size_t k = 0; k < hat_.size(); ++k) {
      const std::complex<double> z = std::complex<double>(spectrum_[k][0], spectrum_[k][1]) * hat_[k];
      spectrum_[k][0] = z.real();
      spectrum_[k][1] = z.imag();
    }
    fftw_execute(backward_);
    Eigen::VectorXd out(static_cast<Eigen::Index>(n_));
    for (std::size_t i = 0; i < n_; ++i) out[static_cast<Eigen::Index>(i)] = real_[i];
    return out;
  }

  std::size_t n_ = 0, size_ = 0;
  double* real_ = nullptr;             // the transforms' real side (length size_)
  fftw_complex* spectrum_ = nullptr;   // their half spectrum (size_ / 2 + 1)
  fftw_plan forward_ = nullptr, backward_ = nullptr;
  std::vector<std::complex<double>> hat_;  // c's half spectrum over size_
};

}  // namespace rhabel::punch::detail
