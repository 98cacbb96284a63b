#include "math/dual.hpp"

#include <doctest/doctest.h>

#include <random>

#include "finite_differences.hpp"
#include "math/rotation.hpp"

namespace xshell::test {

using xshell::test::check_gradient;
using xshell::test::check_hessian;

namespace {
// A function exercising every operation of Dual.
template <class T>
T composite(const T* x) {
  using std::atan2;
  using std::cos;
  using std::sin;
  using std::sqrt;
  const T a = x[0] * x[1] - x[2] / (1.5 + x[0] * x[0]);
  return sqrt(2.0 + a * a) * sin(x[1]) + cos(x[2] - 0.3) / x[3] + atan2(x[0] + 0.1, x[3] - x[2]) -
         3.0 * a;
}

template <int N, class F>
Dual<N> evaluate(const Eigen::VectorXd& x, F f) {
  std::array<Dual<N>, N> xd;
  for (int i = 0; i < N; ++i) xd[i] = Dual<N>::variable(i, x[i]);
  return f(xd.data());
}
}  // namespace

TEST_CASE("Dual gives the exact gradient and Hessian of a composite function") {
  std::mt19937 rng(7);
  int checked = 0;
  for (int trial = 0; trial < 5; ++trial) {
    Eigen::VectorXd x = xshell::test::random_vector(4, rng);
    x[3] = 2.0 + x[3];  // keep away from the division's pole
    const auto f = [](const Eigen::VectorXd& y) { return composite(y.data()); };
    const auto g = [](const Eigen::VectorXd& y) {
      const Dual<4> d = evaluate<4>(y, [](const Dual<4>* z) { return composite(z); });
      return Eigen::VectorXd(d.g);
    };
    const Dual<4> d = evaluate<4>(x, [](const Dual<4>* z) { return composite(z); });
    CHECK(d.v == doctest::Approx(f(x)).epsilon(1e-14));
    const auto rg = check_gradient(f, x, d.g, 1e-6);
    const auto rh = check_hessian(g, x, d.h, 1e-6);
    CHECK(rg.relative_error() < 1e-8);
    CHECK(rh.relative_error() < 1e-7);
    CHECK((d.h - d.h.transpose()).norm() < 1e-12 * d.h.norm());
    checked += rg.compared + rh.compared;
  }
  CHECK(checked == 5 * (4 + 16));
}

TEST_CASE("Rotation by a rotation vector: value and derivatives at and near zero") {
  std::mt19937 rng(3);
  const Eigen::Vector3d v(0.3, -1.2, 0.7);
  int checked = 0;
  // Rotation vectors from exactly zero through the series threshold to large.
  for (double scale : {0.0, 1e-5, 1e-3, 2e-3, 0.1, 1.0, 2.5}) {
    Eigen::Vector3d w = scale * Eigen::Vector3d(0.48, -0.6, 0.64);
    const Eigen::Matrix3d r = rotation_matrix(w);
    CHECK((r.transpose() * r - Eigen::Matrix3d::Identity()).norm() < 1e-14);
    CHECK(r.determinant() == doctest::Approx(1.0));
    if (scale > 0) {
      // Compare with Eigen's angle-axis.
      const Eigen::Matrix3d ref = Eigen::AngleAxisd(w.norm(), w.normalized()).toRotationMatrix();
      CHECK((r - ref).norm() < 1e-14);
    }
    for (int k = 0; k < 3; ++k) {
      const auto component = [&](const auto* z) {
        using T = std::decay_t<decltype(*z)>;
        return rotate(V3<T>(z[0], z[1], z[2]), lift<T>(v)).x * (k == 0) +
               rotate(V3<T>(z[0], z[1], z[2]), lift<T>(v)).y * (k == 1) +
               rotate(V3<T>(z[0], z[1], z[2]), lift<T>(v)).z * (k == 2);
      };
      const auto f = [&](const Eigen::VectorXd& y) { return component(y.data()); };
      const auto g = [&](const Eigen::VectorXd& y) {
        return Eigen::VectorXd(evaluate<3>(y, [&](const Dual<3>* z) { return component(z); }).g);
      };
      const Dual<3> d = evaluate<3>(w, [&](const Dual<3>* z) { return component(z); });
      // Finite differences straddle the series threshold harmlessly: both
      // branches agree to round-off.
      const auto rg = check_gradient(f, w, d.g, 1e-6);
      const auto rh = check_hessian(g, w, d.h, 1e-5);
      CHECK(rg.max_abs_error < 1e-9);
      CHECK(rh.max_abs_error < 1e-8);
      checked += rg.compared + rh.compared;
    }
  }
  // At w = 0: dR/dw v = -[v]x, i.e. d(Rv)/dw_j = e_j x v.
  const Dual<3> dx = evaluate<3>(Eigen::Vector3d::Zero(), [&](const Dual<3>* z) {
    return rotate(V3<Dual<3>>(z[0], z[1], z[2]), lift<Dual<3>>(v)).x;
  });
  CHECK(dx.g[1] == doctest::Approx(v.z()));
  CHECK(dx.g[2] == doctest::Approx(-v.y()));
  CHECK(checked == 7 * 3 * (3 + 9));
}

TEST_CASE("Parallel transport takes a to b, preserves lengths and fixes a x b") {
  std::mt19937 rng(11);
  for (int trial = 0; trial < 20; ++trial) {
    const Eigen::Vector3d a = xshell::test::random_vector(3, rng).normalized();
    const Eigen::Vector3d b = xshell::test::random_vector(3, rng).normalized();
    if (a.dot(b) < -0.9) continue;
    const Eigen::Vector3d v = xshell::test::random_vector(3, rng);
    const Eigen::Vector3d pa =
        parallel_transport(V3<double>(a), V3<double>(b), V3<double>(a)).values();
    const Eigen::Vector3d pv =
        parallel_transport(V3<double>(a), V3<double>(b), V3<double>(v)).values();
    const Eigen::Vector3d axis = a.cross(b);
    const Eigen::Vector3d paxis =
        parallel_transport(V3<double>(a), V3<double>(b), V3<double>(axis)).values();
    CHECK((pa - b).norm() < 1e-14);
    CHECK(pv.norm() == doctest::Approx(v.norm()).epsilon(1e-13));
    CHECK((paxis - axis).norm() < 1e-14);
  }
}

}  // namespace xshell::test
