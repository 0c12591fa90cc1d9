// The joints' pseudo-inverse (psd_pseudo_inverse.hpp): argil's (the range
// found first where the rank is low) against Eigen's eigendecomposition of
// the whole matrix (the code before, and the peer), in the same run, on matrices shaped like the
// real joints of face_recognition_sample_part.stp, sliced_cylinder.step and screw.step: 216 to 384
// rows, 72 to 384 eigenvalues kept, the spectrum running on past the floor of 1e-10 as theirs does.
// Usage: bench_pseudo_inverse [calls per shape, default 30]
#include <Eigen/QR>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <vector>

#include "argil/core/linalg/psd_pseudo_inverse.hpp"
#include "bench_timing.hpp"

namespace {

using argil::PseudoInverseMethod;

struct Shape {
  int size;
  int nonzero;      // eigenvalues log-spaced from 1 down to `smallest`; the rest zero
  double smallest;  // 1e-13: about 10/13 of them above the floor
  const char* like;
};

const Shape kShapes[] = {{360, 94, 1e-13, "a wall or cylinder edge, 72 of 360"},
                         {384, 130, 1e-13, "face_recognition 9-13, 100 of 384"},
                         {384, 191, 1e-13, "face_recognition 10-13, 147 of 384"},
                         {216, 188, 1e-13, "a wall edge, 145 of 216"},
                         {384, 299, 1e-13, "screw 5-6, 230 of 384"},
                         {384, 369, 1e-13, "screw 3-5, 284 of 384"},
                         {384, 384, 2e-8, "face_recognition 6-10, all 384"}};

Eigen::MatrixXd matrix(const Shape& shape, std::mt19937_64& rng) {
  std::normal_distribution<double> gauss;
  Eigen::MatrixXd a(shape.size, shape.size);
  for (Eigen::Index i = 0; i < a.size(); ++i) a.data()[i] = gauss(rng);
  const Eigen::MatrixXd q = Eigen::HouseholderQR<Eigen::MatrixXd>(a).householderQ();
  Eigen::VectorXd mu = Eigen::VectorXd::Zero(shape.size);
  for (int k = 0; k < shape.nonzero; ++k)
    mu[k] = std::pow(shape.smallest,
                     shape.nonzero > 1 ? static_cast<double>(k) / (shape.nonzero - 1) : 0.0);
  const Eigen::MatrixXd g = q * mu.asDiagonal() * q.transpose();
  return 0.5 * (g + g.transpose());
}

}  // namespace

int main(int argc, char** argv) {
  const int calls = argc > 1 ? std::max(1, std::atoi(argv[1])) : 30;
  std::mt19937_64 rng(2026);
  std::printf(
      "psd_pseudo_inverse_factor, floor 1e-10, thread CPU time per call, %d calls each,"
      " interleaved\n",
      calls);
  std::printf("%-5s %-5s %-37s | %-27s | %-27s | %s\n", "rows", "kept", "like", "argil p50 / p99.9",
              "eigen of whole p50 / p99.9", "whole / argil");
  for (const Shape& shape : kShapes) {
    const Eigen::MatrixXd g = matrix(shape, rng);
    std::vector<double> first, whole;
    Eigen::Index kept = -1;
    for (int c = 0; c < calls; ++c) {
      for (const PseudoInverseMethod method :
           {PseudoInverseMethod::automatic, PseudoInverseMethod::eigen_of_whole}) {
        const double t0 = argil::bench::thread_cpu_us();
        const Eigen::MatrixXd f = argil::psd_pseudo_inverse_factor(g, 1e-10, method);
        const double t1 = argil::bench::thread_cpu_us();
        (method == PseudoInverseMethod::automatic ? first : whole).push_back(t1 - t0);
        if (kept >= 0 && f.cols() != kept) {
          std::fprintf(stderr, "the two methods keep %ld and %ld eigenpairs\n",
                       static_cast<long>(kept), static_cast<long>(f.cols()));
          return 1;
        }
        kept = f.cols();
      }
    }
    const argil::bench::Percentiles a = argil::bench::percentiles(first);
    const argil::bench::Percentiles b = argil::bench::percentiles(whole);
    std::printf("%-5d %-5ld %-37s | %12s / %-12s | %12s / %-12s | %.2f\n", shape.size,
                static_cast<long>(kept), shape.like, argil::bench::time_text(a.p50).c_str(),
                argil::bench::time_text(a.p999).c_str(), argil::bench::time_text(b.p50).c_str(),
                argil::bench::time_text(b.p999).c_str(), b.p50 / a.p50);
  }
  return 0;
}
