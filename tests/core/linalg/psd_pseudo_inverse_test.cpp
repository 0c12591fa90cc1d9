// psd_pseudo_inverse_factor against Eigen's eigendecomposition of the whole
// matrix (the oracle), on matrices built from chosen spectra: low and full
// rank, eigenvalues spread across the floor, scales from 1e-12 to 1e12, and
// the empty and zero matrices.
#include <Eigen/Eigenvalues>
#include <Eigen/QR>
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "argil/core/linalg/psd_pseudo_inverse.hpp"

namespace argil {
namespace {

constexpr double kFloor = 1e-10;

/// Q diag(spectrum) Q^T for a random orthogonal Q (size = spectrum's).
Eigen::MatrixXd with_spectrum(std::mt19937_64& rng, const std::vector<double>& spectrum) {
  const auto m = static_cast<Eigen::Index>(spectrum.size());
  std::normal_distribution<double> gauss;
  Eigen::MatrixXd a(m, m);
  for (Eigen::Index i = 0; i < a.size(); ++i) a.data()[i] = gauss(rng);
  const Eigen::MatrixXd q = Eigen::HouseholderQR<Eigen::MatrixXd>(a).householderQ();
  Eigen::MatrixXd g =
      q * Eigen::Map<const Eigen::VectorXd>(spectrum.data(), m).asDiagonal() * q.transpose();
  return 0.5 * (g + g.transpose());
}

/// G^+ by the oracle: eigenpairs of G above the floor.
Eigen::MatrixXd oracle_pseudo_inverse(const Eigen::MatrixXd& g) {
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(g);
  const Eigen::VectorXd& mu = eigen.eigenvalues();
  const double least = kFloor * mu.cwiseAbs().maxCoeff();
  Eigen::MatrixXd out = Eigen::MatrixXd::Zero(g.rows(), g.cols());
  for (Eigen::Index k = 0; k < mu.size(); ++k) {
    if (mu[k] > least)
      out += eigen.eigenvectors().col(k) * eigen.eigenvectors().col(k).transpose() / mu[k];
  }
  return out;
}

/// `rank` eigenvalues log-spaced from `top` down to `top * smallest`, the
/// rest zero, in random order.
std::vector<double> spectrum(std::mt19937_64& rng, int size, int rank, double top,
                             double smallest) {
  std::vector<double> mu(static_cast<std::size_t>(size), 0.0);
  for (int k = 0; k < rank; ++k) {
    const double t = rank > 1 ? static_cast<double>(k) / (rank - 1) : 0.0;
    mu[static_cast<std::size_t>(k)] = top * std::pow(smallest, t);
  }
  std::shuffle(mu.begin(), mu.end(), rng);
  return mu;
}

const PseudoInverseMethod kMethods[] = {PseudoInverseMethod::automatic,
                                        PseudoInverseMethod::range_first,
                                        PseudoInverseMethod::eigen_of_whole};

TEST_CASE("pseudo-inverse factor matches the oracle on well separated spectra",
          "[linalg][pseudo_inverse]") {
  std::mt19937_64 rng(20261201);
  // (size, rank): low rank takes the range first, high rank the whole.
  const std::vector<std::pair<int, int>> shapes{{1, 1},   {2, 1},   {5, 5},    {40, 7},
                                                {60, 60}, {96, 30}, {120, 100}};
  for (const auto& [size, rank] : shapes) {
    for (const double top : {1e-12, 1.0, 1e12}) {
      // Kept eigenvalues down to 1e-6 of the largest, far above the floor.
      const Eigen::MatrixXd g = with_spectrum(rng, spectrum(rng, size, rank, top, 1e-6));
      const Eigen::MatrixXd expected = oracle_pseudo_inverse(g);
      for (const PseudoInverseMethod method : kMethods) {
        CAPTURE(size, rank, top, static_cast<int>(method));
        const Eigen::MatrixXd f = psd_pseudo_inverse_factor(g, kFloor, method);
        CHECK(f.rows() == size);
        CHECK(f.cols() == rank);
        const Eigen::MatrixXd got = f * f.transpose();
        // G^+'s entries reach 1e6 / top; rounding in G is amplified by up
        // to the kept condition number (1e6).
        CHECK((got - expected).norm() <= 1e-8 * expected.norm());
        // The Moore-Penrose identity G G^+ G = G.
        CHECK((g * got * g - g).norm() <= 1e-9 * g.norm());
      }
    }
  }
}

TEST_CASE("pseudo-inverse factor drops the eigenvalues under the floor",
          "[linalg][pseudo_inverse]") {
  std::mt19937_64 rng(7);
  for (const int size : {30, 100}) {
    // Eigenvalues from 1 down to 1e-14: the floor cuts the spectrum, as on
    // real joints. None lies within a factor 3 of the floor, so the count is
    // the oracle's whatever rounding does.
    std::vector<double> mu;
    for (int k = 0; k < size; ++k) {
      const double v = std::pow(1e-14, static_cast<double>(k) / (size - 1));
      if (std::abs(std::log10(v / kFloor)) > std::log10(3.0)) mu.push_back(v);
    }
    const auto above = std::count_if(mu.begin(), mu.end(), [](double v) { return v > kFloor; });
    std::shuffle(mu.begin(), mu.end(), rng);
    const Eigen::MatrixXd g = with_spectrum(rng, mu);
    const Eigen::MatrixXd expected = oracle_pseudo_inverse(g);
    for (const PseudoInverseMethod method : kMethods) {
      CAPTURE(size, static_cast<int>(method));
      const Eigen::MatrixXd f = psd_pseudo_inverse_factor(g, kFloor, method);
      CHECK(f.cols() == above);
      // Applied to a right-hand side in G's range: the multipliers agree to
      // what the kept condition number (3e9) leaves of rounding.
      Eigen::VectorXd x(g.rows());
      std::normal_distribution<double> gauss;
      for (Eigen::Index i = 0; i < x.size(); ++i) x[i] = gauss(rng);
      const Eigen::VectorXd b = g * x;
      const Eigen::VectorXd want = expected * b, got = f * (f.transpose() * b);
      CHECK((got - want).norm() <= 1e-6 * want.norm());
      // G applied to the multipliers gives back b, less its part in the
      // dropped directions (at most 1e-10 of b's size here).
      CHECK((g * got - b).norm() <= 1e-9 * b.norm());
    }
  }
}

/// A joint's G dumped from a session (tests/data/README.md): an int64 size
/// n, then n * n doubles, column by column.
Eigen::MatrixXd read_matrix(const std::string& name) {
  std::ifstream in(std::string(ARGIL_TEST_DATA_DIR) + "/" + name, std::ios::binary);
  std::int64_t n = 0;
  in.read(reinterpret_cast<char*>(&n), sizeof n);
  REQUIRE(in);
  REQUIRE(n > 0);
  Eigen::MatrixXd g(n, n);
  in.read(reinterpret_cast<char*>(g.data()),
          static_cast<std::streamsize>(sizeof(double) * static_cast<std::size_t>(g.size())));
  REQUIRE(in);
  return g;
}

TEST_CASE("pseudo-inverse factor of a real joint's G matches the whole decomposition",
          "[linalg][pseudo_inverse]") {
  // 108 rows, 44 eigenvalues kept, the spectrum running on past the floor.
  // Eigenpairs of L^T L mapped through L were 1e-4 off here; through Q R
  // they are within 1e-6, as close as G's rounding lets the whole come to
  // itself.
  const Eigen::MatrixXd g = read_matrix("joints/face_recognition_joint_g.bin");
  const Eigen::MatrixXd whole =
      psd_pseudo_inverse_factor(g, kFloor, PseudoInverseMethod::eigen_of_whole);
  const Eigen::MatrixXd range =
      psd_pseudo_inverse_factor(g, kFloor, PseudoInverseMethod::range_first);
  CHECK(whole.cols() == 44);
  CHECK(range.cols() == whole.cols());
  std::mt19937_64 rng(15);
  std::normal_distribution<double> gauss;
  for (int k = 0; k < 10; ++k) {
    Eigen::VectorXd x(g.rows());
    for (Eigen::Index i = 0; i < x.size(); ++i) x[i] = gauss(rng);
    const Eigen::VectorXd b = g * x;
    const Eigen::VectorXd want = whole * (whole.transpose() * b);
    const Eigen::VectorXd got = range * (range.transpose() * b);
    CHECK((got - want).norm() <= 1e-5 * want.norm());
  }
  // Its rank at the range's cut is under 3/5 of its size: automatic takes the range.
  CHECK(psd_pseudo_inverse_factor(g, kFloor) == range);
}

TEST_CASE("pseudo-inverse factor takes the range up to 3/5 of the size, then the whole",
          "[linalg][pseudo_inverse]") {
  std::mt19937_64 rng(35);
  for (const int rank : {30, 31}) {  // of 50: 3/5 is 30
    const Eigen::MatrixXd g = with_spectrum(rng, spectrum(rng, 50, rank, 1.0, 1e-3));
    const Eigen::MatrixXd automatic = psd_pseudo_inverse_factor(g, kFloor);
    const PseudoInverseMethod expected =
        rank <= 30 ? PseudoInverseMethod::range_first : PseudoInverseMethod::eigen_of_whole;
    CAPTURE(rank);
    CHECK(automatic == psd_pseudo_inverse_factor(g, kFloor, expected));
  }
}

TEST_CASE("pseudo-inverse factor of a matrix with a NaN or an infinity is empty",
          "[linalg][pseudo_inverse]") {
  std::mt19937_64 rng(11);
  const Eigen::MatrixXd g = with_spectrum(rng, spectrum(rng, 50, 10, 1.0, 1e-3));
  for (const double bad :
       {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()}) {
    for (const PseudoInverseMethod method : kMethods) {
      // Off the diagonal, where the range's pivots may never read it.
      Eigen::MatrixXd h = g;
      h(3, 40) = h(40, 3) = bad;
      CAPTURE(bad, static_cast<int>(method));
      const Eigen::MatrixXd f = psd_pseudo_inverse_factor(h, kFloor, method);
      CHECK(f.rows() == 50);
      CHECK(f.cols() == 0);
    }
  }
}

TEST_CASE("pseudo-inverse factor of empty, zero and rank-one matrices",
          "[linalg][pseudo_inverse]") {
  for (const PseudoInverseMethod method : kMethods) {
    CAPTURE(static_cast<int>(method));
    const Eigen::MatrixXd empty(0, 0);
    CHECK(psd_pseudo_inverse_factor(empty, kFloor, method).size() == 0);
    const Eigen::MatrixXd zero = Eigen::MatrixXd::Zero(6, 6);
    const Eigen::MatrixXd f0 = psd_pseudo_inverse_factor(zero, kFloor, method);
    CHECK(f0.rows() == 6);
    CHECK(f0.cols() == 0);
    // v v^T: pseudo-inverse v v^T / |v|^4.
    const Eigen::VectorXd v = Eigen::VectorXd::LinSpaced(6, -2.0, 3.0);
    const Eigen::MatrixXd f1 = psd_pseudo_inverse_factor(v * v.transpose(), kFloor, method);
    REQUIRE(f1.cols() == 1);
    const Eigen::MatrixXd expected = v * v.transpose() / std::pow(v.squaredNorm(), 2);
    CHECK((f1 * f1.transpose() - expected).norm() <= 1e-14 * expected.norm());
  }
}

}  // namespace
}  // namespace argil
