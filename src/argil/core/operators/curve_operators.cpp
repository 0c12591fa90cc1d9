#include "argil/core/operators/curve_operators.hpp"

#include <algorithm>
#include <cassert>

#include "argil/core/geometry/basis.hpp"
#include "argil/core/geometry/bspline_surface.hpp"

namespace argil {

namespace {

SamplingRows make_rows(int p, const Eigen::VectorXd& U, const Eigen::VectorXd& params) {
  const int n = static_cast<int>(U.size()) - p - 1;
  const Eigen::Index count = params.size();
  SamplingRows rows;
  rows.params = params.cwiseMax(U[p]).cwiseMin(U[n]);
  rows.first_pole.resize(static_cast<std::size_t>(count));
  rows.values.resize(count, p + 1);
  rows.d1.resize(count, p + 1);
  rows.d2.resize(count, p + 1);
  Eigen::MatrixXd ders(3, p + 1);
  for (Eigen::Index k = 0; k < count; ++k) {
    const int span = find_span(p, U, n, rows.params[k]);
    basis_derivatives(p, U, span, rows.params[k], 2, ders);
    rows.first_pole[static_cast<std::size_t>(k)] = span - p;
    rows.values.row(k) = ders.row(0);
    rows.d1.row(k) = ders.row(1);
    rows.d2.row(k) = ders.row(2);
  }
  return rows;
}

BandedMatrix collocation_matrix(int p, const SamplingRows& rows) {
  const int n = static_cast<int>(rows.size());
  int lower = 0;
  int upper = 0;
  for (int i = 0; i < n; ++i) {
    const int first = rows.first_pole[static_cast<std::size_t>(i)];
    lower = std::max(lower, i - first);
    upper = std::max(upper, first + p - i);
  }
  BandedMatrix a(n, lower, upper);
  for (int i = 0; i < n; ++i) {
    const int first = rows.first_pole[static_cast<std::size_t>(i)];
    for (int r = 0; r <= p; ++r) a.at(i, first + r) = rows.values(i, r);
  }
  return a;
}

}  // namespace

Result<std::shared_ptr<const CurveOperators>> CurveOperators::build(int degree,
                                                                    const Eigen::VectorXd& knots) {
  std::shared_ptr<CurveOperators> ops(new CurveOperators());
  ops->degree_ = degree;
  ops->knots_ = knots;
  ops->extraction_ = bezier_extraction(degree, knots);
  ops->subdivision_ = subdivision_matrices(degree);
  ops->greville_ = greville_abscissae(degree, knots);
  ops->greville_rows_ = make_rows(degree, knots, ops->greville_);
  Result<BandedLU> lu = BandedLU::factorize(collocation_matrix(degree, ops->greville_rows_));
  if (!lu.ok()) {
    Status s = lu.status();
    s.message = "collocation at the Greville abscissae: " + s.message;
    return s;
  }
  ops->collocation_ = std::move(lu).value();
  return std::shared_ptr<const CurveOperators>(std::move(ops));
}

const SamplingRows& CurveOperators::level_rows(int level) const {
  assert(level >= 0 && level < 30);
  std::lock_guard<std::mutex> lock(levels_mutex_);
  if (levels_.size() <= static_cast<std::size_t>(level)) {
    levels_.resize(static_cast<std::size_t>(level) + 1);
  }
  std::unique_ptr<SamplingRows>& slot = levels_[static_cast<std::size_t>(level)];
  if (!slot) {
    const int steps = 1 << level;
    const int elements = element_count();
    Eigen::VectorXd params(elements * steps + 1);
    for (int e = 0; e < elements; ++e) {
      const int s = extraction_.spans[static_cast<std::size_t>(e)];
      const double a = knots_[s];
      const double b = knots_[s + 1];
      for (int k = 0; k < steps; ++k) {
        // a + (b - a) * k / steps, exact at k = 0 so element starts hit knots.
        params[e * steps + k] = a + (b - a) * (static_cast<double>(k) / steps);
      }
    }
    params[elements * steps] = knots_[count()];
    slot = std::make_unique<SamplingRows>(make_rows(degree_, knots_, params));
  }
  return *slot;
}

SamplingRows CurveOperators::sampling_rows(const Eigen::VectorXd& params) const {
  return make_rows(degree_, knots_, params);
}

Result<std::shared_ptr<const CurveOperators>> OperatorCache::get(int degree,
                                                                 const Eigen::VectorXd& knots) {
  Key key{degree, std::vector<double>(knots.data(), knots.data() + knots.size())};
  std::lock_guard<std::mutex> lock(mutex_);
  auto found = entries_.find(key);
  if (found != entries_.end()) return found->second;
  Result<std::shared_ptr<const CurveOperators>> built = CurveOperators::build(degree, knots);
  if (built.ok()) entries_.emplace(std::move(key), built.value());
  return built;
}

std::size_t OperatorCache::size() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return entries_.size();
}

}  // namespace argil
