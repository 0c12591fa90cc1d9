// BandedLU and BandedCholesky against Eigen's dense PartialPivLU and LLT as the
// oracle, over every band shape of small systems (n = 1 and the full band
// included), and their failure reports on singular or indefinite matrices.
#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <catch2/catch.hpp>
#include <limits>
#include <random>

#include "argil/core/linalg/banded_cholesky.hpp"
#include "argil/core/linalg/banded_lu.hpp"

namespace argil {
namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();
const std::vector<int> kSizes{1, 2, 3, 4, 7, 12, 20};

// Random entries in [-1, 1] inside the band, and a diagonal that dominates its
// row and column: LU without pivoting is stable there (as on the collocation
// matrices it is made for), so any disagreement with the oracle is a bug.
BandedMatrix random_banded(std::mt19937_64& rng, int n, int lower, int upper) {
  std::uniform_real_distribution<double> entry(-1.0, 1.0);
  BandedMatrix a(n, lower, upper);
  for (int j = 0; j < n; ++j) {
    for (int i = std::max(0, j - upper); i <= std::min(n - 1, j + lower); ++i) {
      a.at(i, j) = entry(rng);
    }
  }
  for (int k = 0; k < n; ++k) a.at(k, k) = (entry(rng) < 0 ? -1.0 : 1.0) * (lower + upper + 1.5);
  return a;
}

Eigen::MatrixXd dense(const BandedMatrix& a) {
  Eigen::MatrixXd m(a.size, a.size);
  for (int i = 0; i < a.size; ++i) {
    for (int j = 0; j < a.size; ++j) m(i, j) = a.at(i, j);
  }
  return m;
}

// Symmetric, band `bandwidth`, diagonal dominant with a positive diagonal: SPD.
SymmetricBandMatrix random_spd(std::mt19937_64& rng, int n, int bandwidth) {
  std::uniform_real_distribution<double> entry(-1.0, 1.0);
  SymmetricBandMatrix a(n, bandwidth);
  for (int i = 0; i < n; ++i) {
    for (int j = std::max(0, i - bandwidth); j < i; ++j) a.at(i, j) = entry(rng);
    a.at(i, i) = 2.0 * bandwidth + 1.0 + std::abs(entry(rng));
  }
  return a;
}

Eigen::MatrixXd dense(const SymmetricBandMatrix& a) {
  Eigen::MatrixXd m = Eigen::MatrixXd::Zero(a.size(), a.size());
  for (int i = 0; i < a.size(); ++i) {
    for (int j = std::max(0, i - a.bandwidth()); j <= i; ++j) m(i, j) = m(j, i) = a.at(i, j);
  }
  return m;
}

double condition_1norm(const Eigen::MatrixXd& m) {
  return m.cwiseAbs().colwise().sum().maxCoeff() *
         m.inverse().cwiseAbs().colwise().sum().maxCoeff();
}

// Forward error bound of a backward-stable solve: a small multiple of
// n eps cond(A), relative to the solution's size.
double solve_tolerance(const Eigen::MatrixXd& m, const Eigen::MatrixXd& x) {
  return 16.0 * static_cast<double>(m.rows()) * kEps * condition_1norm(m) *
         std::max(1.0, x.cwiseAbs().maxCoeff());
}

}  // namespace

TEST_CASE("banded LU solves A x = b and A^T x = b like dense PartialPivLU, every band shape",
          "[linalg][banded_lu]") {
  std::mt19937_64 rng(41);
  std::uniform_real_distribution<double> entry(-1.0, 1.0);
  for (int n : kSizes) {
    for (int lower = 0; lower < n; ++lower) {
      for (int upper = 0; upper < n; ++upper) {
        const BandedMatrix a = random_banded(rng, n, lower, upper);
        const Eigen::MatrixXd m = dense(a);
        const Eigen::MatrixXd rhs = Eigen::MatrixXd::NullaryExpr(n, 3, [&] { return entry(rng); });
        const Result<BandedLU> lu = BandedLU::factorize(a);
        INFO("n " << n << " lower " << lower << " upper " << upper);
        REQUIRE(lu.status().message == "");
        Eigen::MatrixXd x = rhs;
        lu.value().solve_in_place(x);
        const Eigen::MatrixXd expected = m.partialPivLu().solve(rhs);
        CHECK((x - expected).cwiseAbs().maxCoeff() <= solve_tolerance(m, expected));
        Eigen::MatrixXd xt = rhs;
        lu.value().solve_transpose_in_place(xt);
        const Eigen::MatrixXd expected_t = m.transpose().partialPivLu().solve(rhs);
        CHECK((xt - expected_t).cwiseAbs().maxCoeff() <= solve_tolerance(m, expected_t));
      }
    }
  }
}

TEST_CASE("banded LU's 1-norm condition number matches the dense one", "[linalg][banded_lu]") {
  std::mt19937_64 rng(42);
  for (int n : kSizes) {
    for (int band = 0; band < n; ++band) {
      const BandedMatrix a = random_banded(rng, n, band, n - 1 - band);
      const Result<BandedLU> lu = BandedLU::factorize(a);
      REQUIRE(lu.ok());
      const double expected = condition_1norm(dense(a));
      INFO("n " << n << " lower " << band);
      // Both sides carry rounding of order n eps cond; 1e-10 relative leaves room.
      CHECK(lu.value().condition_1norm() == Approx(expected).epsilon(1e-10));
    }
  }
}

TEST_CASE("banded LU reports a singular matrix or a zero pivot instead of dividing by it",
          "[linalg][banded_lu]") {
  SECTION("all zero") {
    const Result<BandedLU> lu = BandedLU::factorize(BandedMatrix(3, 1, 1));
    REQUIRE_FALSE(lu.ok());
    CHECK(lu.status().code == StatusCode::numerical_failure);
    CHECK_THAT(lu.status().message, Catch::Contains("pivot 0"));
  }
  SECTION("two equal rows") {
    BandedMatrix a(4, 1, 1);
    a.at(0, 0) = a.at(0, 1) = 1.0;
    a.at(1, 0) = a.at(1, 1) = 1.0;
    a.at(2, 1) = a.at(2, 3) = 0.5;
    a.at(2, 2) = a.at(3, 3) = 2.0;
    a.at(3, 2) = 0.5;
    // Rows 0 and 1 are both (1, 1, 0, 0): singular, found at pivot 1.
    REQUIRE(dense(a).row(0) == dense(a).row(1));
    const Result<BandedLU> lu = BandedLU::factorize(a);
    REQUIRE_FALSE(lu.ok());
    CHECK(lu.status().code == StatusCode::numerical_failure);
    CHECK_THAT(lu.status().message, Catch::Contains("pivot 1 of 4"));
  }
}

TEST_CASE("banded Cholesky solves SPD systems like dense LLT, every bandwidth and column count",
          "[linalg][banded_cholesky]") {
  std::mt19937_64 rng(43);
  std::uniform_real_distribution<double> entry(-1.0, 1.0);
  for (int n : kSizes) {
    for (int bandwidth = 0; bandwidth < n; ++bandwidth) {
      const SymmetricBandMatrix a = random_spd(rng, n, bandwidth);
      const Eigen::MatrixXd m = dense(a);
      const Result<BandedCholesky> llt = BandedCholesky::factorize(a);
      INFO("n " << n << " bandwidth " << bandwidth);
      REQUIRE(llt.status().message == "");
      REQUIRE(llt.value().size() == n);
      // 1, 3 and 4 columns have their own unrolled sweeps; 2 and 5 take the general path.
      for (int columns : {1, 2, 3, 4, 5}) {
        const RowMajorMatrix rhs =
            RowMajorMatrix::NullaryExpr(n, columns, [&] { return entry(rng); });
        RowMajorMatrix x = rhs;
        llt.value().solve_in_place(x);
        const Eigen::MatrixXd expected = m.llt().solve(Eigen::MatrixXd(rhs));
        INFO("columns " << columns);
        CHECK((Eigen::MatrixXd(x) - expected).cwiseAbs().maxCoeff() <=
              solve_tolerance(m, expected));
      }
    }
  }
}

TEST_CASE("banded Cholesky reports a matrix that is not positive definite, naming the pivot",
          "[linalg][banded_cholesky]") {
  SECTION("indefinite: eigenvalues 3 and -1") {
    SymmetricBandMatrix a(2, 1);
    a.at(0, 0) = 1.0;
    a.at(1, 0) = 2.0;
    a.at(1, 1) = 1.0;
    const Result<BandedCholesky> llt = BandedCholesky::factorize(a);
    REQUIRE_FALSE(llt.ok());
    CHECK(llt.status().code == StatusCode::numerical_failure);
    CHECK_THAT(llt.status().message, Catch::Contains("pivot 1 of 2"));
  }
  SECTION("negative diagonal") {
    SymmetricBandMatrix a(3, 0);
    a.at(0, 0) = 1.0;
    a.at(1, 1) = 1.0;
    a.at(2, 2) = -1.0;
    const Result<BandedCholesky> llt = BandedCholesky::factorize(a);
    REQUIRE_FALSE(llt.ok());
    CHECK_THAT(llt.status().message, Catch::Contains("pivot 2 of 3"));
  }
  SECTION("singular: rank one") {
    SymmetricBandMatrix a(3, 2);
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j <= i; ++j) a.at(i, j) = 1.0;
    }
    const Result<BandedCholesky> llt = BandedCholesky::factorize(a);
    REQUIRE_FALSE(llt.ok());
    CHECK_THAT(llt.status().message, Catch::Contains("pivot 1 of 3"));
  }
}

}  // namespace argil
