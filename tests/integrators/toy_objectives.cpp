#include "toy_objectives.hpp"

#include <cmath>
#include <limits>

namespace xshell::test {

namespace {

constexpr double kPi = 3.14159265358979323846;

// The 3D position made of x[first], x[first + 1], x[first + 2].
template <class Duals>
std::array<typename Duals::value_type, 3> node(const Duals& x, int first) {
  return {x[static_cast<size_t>(first)], x[static_cast<size_t>(first + 1)],
          x[static_cast<size_t>(first + 2)]};
}

}  // namespace

StencilObjective make_chain(const ChainOptions& o) {
  const int m = o.nodes;
  const double L = o.rest_length;
  const double span = o.span_ratio * (m - 1) * L;
  Eigen::VectorXd x(3 * m);
  for (int k = 0; k < m; ++k) {
    const double s = static_cast<double>(k) / (m - 1);
    x.segment<3>(3 * k) << s * span, 0.02 * std::sin(2.0 * kPi * s), -0.05 * std::sin(kPi * s);
  }
  std::vector<Term> terms;
  for (int k = 0; k + 1 < m; ++k) {
    // Spring: k/2 (l - L)^2 + k4/4 (l - L)^4, l = |x_{k+1} - x_k|.
    terms.push_back(make_term<6>({3 * k, 3 * k + 1, 3 * k + 2, 3 * k + 3, 3 * k + 4, 3 * k + 5},
                                 [o, L](const std::array<Dual<6>, 6>& v) {
                                   const Dual3<6> e = difference(node(v, 3), node(v, 0));
                                   const Dual<6> stretch = sqrt(dot(e, e)) - L;
                                   const Dual<6> s2 = square(stretch);
                                   return 0.5 * o.stretch * s2 + 0.25 * o.quartic * square(s2);
                                 }));
  }
  for (int k = 1; k + 1 < m; ++k) {
    // Bending-like: kb/L (1 - t_a . t_b) with unit tangents t of the two edges.
    std::array<int, 9> dofs;
    for (int i = 0; i < 9; ++i) dofs[static_cast<size_t>(i)] = 3 * (k - 1) + i;
    terms.push_back(make_term<9>(dofs, [o, L](const std::array<Dual<9>, 9>& v) {
      const Dual3<9> a = difference(node(v, 3), node(v, 0));
      const Dual3<9> b = difference(node(v, 6), node(v, 3));
      const Dual<9> cosine = dot(a, b) / sqrt(dot(a, a) * dot(b, b));
      return (o.bending / L) * (1.0 - cosine);
    }));
  }
  for (int k = 1; k + 1 < m; ++k) {
    // Dead loads: potential -f . x.
    terms.push_back(make_term<2>({3 * k + 1, 3 * k + 2}, [o](const std::array<Dual<2>, 2>& v) {
      return o.weight * v[1] - o.side_load * v[0];
    }));
  }
  std::vector<int> pinned = {0, 1, 2, 3 * m - 3, 3 * m - 2, 3 * m - 1};
  return StencilObjective(x, pinned, std::move(terms));
}

StencilObjective make_rosenbrock(int n, double a) {
  Eigen::VectorXd x(n);
  for (int i = 0; i < n; ++i) x[i] = i % 2 == 0 ? -1.2 : 1.0;
  std::vector<Term> terms;
  for (int i = 0; i + 1 < n; i += 2)
    terms.push_back(make_term<2>({i, i + 1}, [a](const std::array<Dual<2>, 2>& v) {
      return a * square(v[1] - square(v[0])) + square(1.0 - v[0]);
    }));
  return StencilObjective(x, {}, std::move(terms));
}

StencilObjective make_column(const ColumnOptions& o) {
  const int N = o.segments;
  const double L = o.length / N;
  const double load = o.load_ratio * kPi * kPi * o.bending / (o.length * o.length);
  Eigen::VectorXd x(2 * (N + 1));
  for (int k = 0; k <= N; ++k) x.segment<2>(2 * k) << k * L, o.imperfection * std::sin(kPi * k / N);
  std::vector<Term> terms;
  for (int k = 0; k < N; ++k)
    terms.push_back(make_term<4>(
        {2 * k, 2 * k + 1, 2 * k + 2, 2 * k + 3}, [o, L](const std::array<Dual<4>, 4>& v) {
          const Dual<4> l = sqrt(square(v[2] - v[0]) + square(v[3] - v[1]));
          return (0.5 * o.stretch / L) * square(l - L);
        }));
  for (int k = 1; k < N; ++k)
    terms.push_back(make_term<6>(
        {2 * k - 2, 2 * k - 1, 2 * k, 2 * k + 1, 2 * k + 2, 2 * k + 3},
        [o, L](const std::array<Dual<6>, 6>& v) {
          const Dual<6> ax = v[2] - v[0], ay = v[3] - v[1], bx = v[4] - v[2], by = v[5] - v[3];
          const Dual<6> cosine =
              (ax * bx + ay * by) / sqrt((ax * ax + ay * ay) * (bx * bx + by * by));
          return (o.bending / L) * (1.0 - cosine);
        }));
  // Axial dead load P pushing the roller end towards the pinned end.
  terms.push_back(
      make_term<1>({2 * N}, [load](const std::array<Dual<1>, 1>& v) { return load * v[0]; }));
  return StencilObjective(x, {0, 1, 2 * N + 1}, std::move(terms));
}

int column_middle_y(const ColumnOptions& options) {
  // Unknowns: x_1, y_1, ..., x_{N-1}, y_{N-1}, x_N (node 0 and y_N pinned).
  const int middle = options.segments / 2;
  return 2 * (middle - 1) + 1;
}

OffsetObjective::OffsetObjective(Objective& inner, double alpha)
    : inner_(inner), alpha_(alpha), base_(inner.get()), d_(Eigen::VectorXd::Zero(inner.size())) {
  hessian_ = inner_.hessian();
  for (int j = 0; j < hessian_.outerSize(); ++j) {
    bool has_diagonal = false;
    for (Eigen::SparseMatrix<double>::InnerIterator it(hessian_, j); it; ++it)
      has_diagonal = has_diagonal || it.row() == j;
    if (!has_diagonal)
      throw std::invalid_argument("OffsetObjective: Hessian pattern lacks a diagonal entry");
  }
}

void OffsetObjective::set(const Eigen::VectorXd& d) {
  if (!((1.0 + 2.0 * alpha_ * d.array()) > 0.0).all())
    throw std::domain_error("OffsetObjective: offset outside the invertible range");
  d_ = d;
  inner_.set(base_ + d_ + alpha_ * d_.cwiseProduct(d_));
}

Eigen::VectorXd OffsetObjective::gradient() const {
  // dE/dd = J^T g, J = diag(1 + 2 alpha d).
  return jacobian_diagonal().cwiseProduct(inner_.gradient());
}

const Eigen::SparseMatrix<double>& OffsetObjective::hessian() {
  // d2E/dd2 = J H J + diag(2 alpha g).
  const Eigen::SparseMatrix<double>& H = inner_.hessian();
  const Eigen::VectorXd J = jacobian_diagonal();
  const Eigen::VectorXd g = inner_.gradient();
  hessian_ = H;
  for (int j = 0; j < hessian_.outerSize(); ++j)
    for (Eigen::SparseMatrix<double>::InnerIterator it(hessian_, j); it; ++it) {
      it.valueRef() *= J[it.row()] * J[j];
      if (it.row() == j) it.valueRef() += 2.0 * alpha_ * g[j];
    }
  return hessian_;
}

void OffsetObjective::rebase(Eigen::VectorXd* velocity) {
  // x' = J d': after the rebase J = I, so the new offset velocity is J d'.
  if (velocity != nullptr) *velocity = jacobian_diagonal().cwiseProduct(*velocity);
  base_ = inner_.get();
  d_.setZero();
  ++rebases_;
}

SqrtWell::SqrtWell(Eigen::VectorXd x0, InvalidBehaviour behaviour, double invalid_below)
    : x_(std::move(x0)), behaviour_(behaviour), invalid_below_(invalid_below) {
  hessian_.resize(x_.size(), x_.size());
  std::vector<Eigen::Triplet<double>> diagonal;
  for (Eigen::Index i = 0; i < x_.size(); ++i) diagonal.emplace_back(i, i, 1.0);
  hessian_.setFromTriplets(diagonal.begin(), diagonal.end());
  hessian_.makeCompressed();
}

bool SqrtWell::valid(const Eigen::VectorXd& x) const {
  return ((x.array() > 0.0) && (x.array() >= invalid_below_)).all();
}

void SqrtWell::set(const Eigen::VectorXd& q) {
  if (behaviour_ == InvalidBehaviour::Throw && !valid(q)) {
    ++invalid_;
    throw std::domain_error("SqrtWell: invalid configuration");
  }
  x_ = q;
}

double SqrtWell::energy() const {
  if (!valid(x_)) return ++invalid_, std::numeric_limits<double>::quiet_NaN();
  return (x_.array() - 2.0 * x_.array().sqrt()).sum();
}

Eigen::VectorXd SqrtWell::gradient() const {
  if (!valid(x_)) return ++invalid_, Eigen::VectorXd::Constant(size(), std::nan(""));
  return (1.0 - x_.array().rsqrt()).matrix();
}

const Eigen::SparseMatrix<double>& SqrtWell::hessian() {
  for (Eigen::Index i = 0; i < size(); ++i)
    hessian_.coeffRef(i, i) = valid(x_) ? 0.5 * std::pow(x_[i], -1.5) : std::nan("");
  return hessian_;
}

}  // namespace xshell::test
