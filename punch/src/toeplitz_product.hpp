// punch/src/toeplitz_product.hpp: products with a Toeplitz matrix by FFT (internal to punch/src).
//
// WHAT IT COMPUTES. y = T v for the n x n matrix T(i, j) = t[j - i + n - 1] (t: its 2n - 1
// diagonals, the action of panel j at the collocation point i of a uniform boundary-element
// grid), and the same product restricted to a subset of rows and columns (the active panels of a
// contact search: zero outside the columns, read at the rows). T is embedded in a circulant of
// size M >= 2n - 1 (a power of two), whose product is a cyclic convolution: y = ifft(fft(c) .*
// fft(v)) with c[k] = t[n - 1 - k] (k = i - j >= 0) and c[M - k] = t[n - 1 + k] (k = j - i > 0).
// A matrix that is itself circulant (a periodic grid: t[n - 1 + k] = t[k - 1] for k > 0) is taken
// as it is, M = n, when n is a multiple of 4 whose other prime factors are 2, 3 and 5 (kissfft's
// fast radices; its real transform halves a length divisible by 4): about a third of the padded
// work at n = 1e5 2^k. The transforms are real (half spectra).
// O(M log M) a product instead of O(n^2); memory O(M).
//
// ACCURACY. The FFT's rounding: |y - T v| <~ eps log2(M) max|t| sum|v| (Eigen's FFT, kissfft
// backend). Near that floor a product is no longer exact where y is small against the data; the
// contact search compares penetrations with 1e-9 of the profile's span, far above it.
//
// Not thread-safe (the FFT's plan cache and work arrays are members): one object per thread.
#pragma once

#include <Eigen/Dense>
#include <unsupported/Eigen/FFT>

#include <complex>
#include <cstddef>
#include <vector>

namespace rhabel::punch::detail {

class toeplitz_product {
 public:
  /// t: the 2n - 1 diagonals, t[j - i + n - 1] = T(i, j); circulant: T is (see the top of the file).
  toeplitz_product(const std::vector<double>& t, std::size_t n, bool circulant = false) : n_(n) {
    fft_.SetFlag(Eigen::FFT<double>::HalfSpectrum);
    std::vector<double> c;
    if (circulant && fast_length(n_)) {
      size_ = n_;
      c.resize(size_);
      for (std::size_t k = 0; k < n_; ++k) c[k] = t[n_ - 1 - k];
    } else {
      size_ = 1;
      while (size_ < 2 * n_) size_ *= 2;
      c.assign(size_, 0.0);
      for (std::size_t k = 0; k < n_; ++k) c[k] = t[n_ - 1 - k];
      for (std::size_t k = 1; k < n_; ++k) c[size_ - k] = t[n_ - 1 + k];
    }
    fft_.fwd(hat_, c);
    padded_.assign(size_, 0.0);
  }

  /// The transform's length (2^k >= 2n, or n for a circulant of a fast length).
  std::size_t transform_length() const { return size_; }

  std::size_t size() const { return n_; }

  /// T v, v of length n.
  Eigen::VectorXd apply(const Eigen::VectorXd& v) {
    std::fill(padded_.begin(), padded_.end(), 0.0);
    for (std::size_t j = 0; j < n_; ++j) padded_[j] = v[static_cast<Eigen::Index>(j)];
    return convolve();
  }

  /// (T restricted to the columns `columns`) v, v of length columns.size(): all n rows.
  Eigen::VectorXd apply(const std::vector<std::size_t>& columns, const Eigen::VectorXd& v) {
    std::fill(padded_.begin(), padded_.end(), 0.0);
    for (std::size_t c = 0; c < columns.size(); ++c) padded_[columns[c]] = v[static_cast<Eigen::Index>(c)];
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

  Eigen::VectorXd convolve() {
    fft_.fwd(work_, padded_);
    for (std::size_t k = 0; k < work_.size(); ++k) work_[k] *= hat_[k];
    fft_.inv(result_, work_, static_cast<Eigen::Index>(size_));
    Eigen::VectorXd out(static_cast<Eigen::Index>(n_));
    for (std::size_t i = 0; i < n_; ++i) out[static_cast<Eigen::Index>(i)] = result_[i];
    return out;
  }

  std::size_t n_ = 0, size_ = 0;
  Eigen::FFT<double> fft_;
  std::vector<std::complex<double>> hat_, work_;
  std::vector<double> padded_, result_;
};

}  // namespace rhabel::punch::detail
