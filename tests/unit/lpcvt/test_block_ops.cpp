// The blocked vector work of the minimisation (lpcvt/block_ops.hpp): parallel from 4 blocks on,
// the same bits for 1 and 2 threads, the serial sum's bits for one block.
#include <doctest/doctest.h>

#include <cmath>
#include <random>

#include <omp.h>

#include "helpers.hpp"
#include "lpcvt/block_ops.hpp"

using namespace lpcvt_test;
using Eigen::VectorXd;

TEST_CASE("block ops: dot, sqnorm and axpy give the same bits on 1 and 2 threads; one block is the serial loop") {
  std::mt19937 rng(51);
  std::normal_distribution<double> g(0, 1);
  const Eigen::Index n = 7 * blocks::kBlock + 123;  // 8 blocks: the parallel path
  VectorXd a(n), b(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    a[i] = g(rng) * std::exp(3 * g(rng));  // magnitudes spread: a sum's order shows in its bits
    b[i] = g(rng);
  }
  double d[2], q[2];
  VectorXd y[2] = {b, b};
  {
    const RestoreThreads restore;
    for (int t : {1, 2}) {
      omp_set_num_threads(t);
      d[t - 1] = blocks::dot(a, b);
      q[t - 1] = blocks::sqnorm(a);
      blocks::axpy(0.37, a, y[t - 1]);
    }
  }
  CHECK(d[0] == d[1]);  // bit for bit
  CHECK(q[0] == q[1]);
  CHECK(y[0] == y[1]);
  // the definition: the blocks' sums added in block order
  double ref = 0;
  for (Eigen::Index s = 0; s < n; s += blocks::kBlock) {
    const Eigen::Index e = std::min(n, s + blocks::kBlock);
    ref += a.segment(s, e - s).dot(b.segment(s, e - s));
  }
  CHECK(d[0] == ref);
  CHECK(d[0] == doctest::Approx(a.dot(b)).epsilon(1e-10));
  CHECK(y[0] == b + 0.37 * a);
  // one block: Eigen's own dot, bit for bit
  const VectorXd s1 = a.head(1000), s2 = b.head(1000);
  CHECK(blocks::dot(s1, s2) == s1.dot(s2));
  CHECK(blocks::sqnorm(VectorXd()) == 0.0);
}
