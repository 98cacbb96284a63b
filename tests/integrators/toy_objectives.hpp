// Toy objectives for the integrator tests, each with a known character:
//   - chain: a 3D chain of nonlinear springs with bending-like terms,
//     hanging between two pinned ends under gravity and a side load
//     (one stable equilibrium);
//   - rosenbrock: the extended Rosenbrock function (n/2 curved narrow
//     valleys, indefinite Hessian away from the unique minimum (1, ..., 1));
//   - column: a discrete planar elastica under an axial dead load above
//     Euler's critical load: the straight state is a saddle, the two
//     buckled states are minima;
//   - OffsetObjective: any objective re-expressed with unknowns that are
//     nonlinear offsets from a stored base point; rebase() moves the base to
//     the current configuration and resets the offsets (and transforms the
//     velocity), like the rod model's frame updates;
//   - SqrtWell: a separable convex energy defined only on part of the
//     space; outside it either set() throws std::domain_error or the
//     values are NaN, to test the solvers' failure handling;
//   - Slope: a convex energy unbounded below (no equilibrium: a load that
//     nothing holds), to test that the solvers see divergence;
//   - Quadratic: 1/2 q'Kq - f.q, whose Newton step is exact (for the step
//     caps, the constrained solves' Schur complement).
#pragma once

#include <cmath>
#include <stdexcept>
#include <vector>

#include "integrators/newton/newton.hpp"
#include "stencil_objective.hpp"

namespace xshell::test {

struct ChainOptions {
  int nodes = 12;
  double rest_length = 0.1;
  double span_ratio = 0.85;  // end-to-end distance / total rest length
  double stretch = 100.0;    // k (l - L)^2 / 2
  double quartic = 1e4;      // + k4 (l - L)^4 / 4
  double bending = 0.01;     // kb (1 - t_i . t_j) / L
  double weight = 0.5;       // per node, along -z
  double side_load = 0.2;    // per node, along +y
};
StencilObjective make_chain(const ChainOptions& options = {});

// sum over even i of a (x_{i+1} - x_i^2)^2 + (1 - x_i)^2 (n even), started
// at the classic (-1.2, 1, -1.2, 1, ...).
StencilObjective make_rosenbrock(int n = 8, double a = 100.0);

struct ColumnOptions {
  int segments = 10;
  double length = 1.0;
  double stretch = 1e3;       // EA: EA/(2L) (l - L)^2 per segment
  double bending = 1.0;       // EI: EI/L (1 - t_i . t_j) per hinge
  double load_ratio = 1.3;    // P / (pi^2 EI / length^2)
  double imperfection = 0.0;  // initial lateral deflection amplitude (sine)
};
StencilObjective make_column(const ColumnOptions& options = {});
// Unknown index of the lateral deflection of the middle node.
int column_middle_y(const ColumnOptions& options);

class OffsetObjective : public Objective {
 public:
  // q = offsets d, configuration x = base + d + alpha d^2 (entrywise),
  // valid while 1 + 2 alpha d_i > 0. `inner` must outlive this object and
  // its Hessian pattern must contain the diagonal.
  OffsetObjective(Objective& inner, double alpha = 0.3);

  Eigen::Index size() const override { return inner_.size(); }
  Eigen::VectorXd get() const override { return d_; }
  void set(const Eigen::VectorXd& d) override;
  double energy() const override { return inner_.energy(); }
  Eigen::VectorXd gradient() const override;
  const Eigen::SparseMatrix<double>& hessian() override;
  Eigen::VectorXd gradient_weights() const override { return inner_.gradient_weights(); }
  Eigen::VectorXd mass() const override { return inner_.mass(); }
  void rebase(Eigen::VectorXd* velocity = nullptr) override;

  Eigen::VectorXd configuration() const { return inner_.get(); }
  long rebases() const { return rebases_; }

 private:
  Eigen::VectorXd jacobian_diagonal() const { return (1.0 + 2.0 * alpha_ * d_.array()).matrix(); }

  Objective& inner_;
  double alpha_;
  Eigen::VectorXd base_, d_;
  Eigen::SparseMatrix<double> hessian_;
  long rebases_ = 0;
};

// Forwards to another objective and counts the calls of set(); derived
// classes make some of those calls fail (before_set throws).
class ForwardingObjective : public Objective {
 public:
  explicit ForwardingObjective(Objective& inner) : inner_(inner) {}

  Eigen::Index size() const override { return inner_.size(); }
  Eigen::VectorXd get() const override { return inner_.get(); }
  void set(const Eigen::VectorXd& q) override {
    before_set(++calls_);
    inner_.set(q);
  }
  double energy() const override { return inner_.energy(); }
  Eigen::VectorXd gradient() const override { return inner_.gradient(); }
  const Eigen::SparseMatrix<double>& hessian() override { return inner_.hessian(); }
  Eigen::VectorXd gradient_weights() const override { return inner_.gradient_weights(); }
  Eigen::VectorXd mass() const override { return inner_.mass(); }
  long calls() const { return calls_; }

 protected:
  // Called with the number of this set() call (from 1) before it forwards.
  virtual void before_set(long call) { (void)call; }

 private:
  Objective& inner_;
  long calls_ = 0;
};

// Its set() throws std::runtime_error (not a domain_error: a bug, say) from
// the `fail_at`-th call on.
class FaultyObjective : public ForwardingObjective {
 public:
  FaultyObjective(Objective& inner, long fail_at) : ForwardingObjective(inner), fail_at_(fail_at) {}

 protected:
  void before_set(long call) override {
    if (call >= fail_at_) throw std::runtime_error("FaultyObjective: simulated bug");
  }

 private:
  long fail_at_;
};

// Its set() call number `invalid_call` (from 1; 0: none) throws
// std::domain_error, as the rod model does for a configuration it cannot
// evaluate.
class InvalidAtCall : public ForwardingObjective {
 public:
  InvalidAtCall(Objective& inner, long invalid_call)
      : ForwardingObjective(inner), invalid_call_(invalid_call) {}

 protected:
  void before_set(long call) override {
    if (call == invalid_call_) throw std::domain_error("InvalidAtCall: invalid configuration");
  }

 private:
  long invalid_call_;
};

enum class InvalidBehaviour { Throw, NaN };

class SqrtWell : public Objective {
 public:
  // E = sum_i (x_i - 2 sqrt(x_i)), minimum at x = 1; configurations with
  // some x_i < invalid_below (or x_i <= 0) are invalid.
  SqrtWell(Eigen::VectorXd x0, InvalidBehaviour behaviour, double invalid_below = 0.0);

  Eigen::Index size() const override { return x_.size(); }
  Eigen::VectorXd get() const override { return x_; }
  void set(const Eigen::VectorXd& q) override;
  double energy() const override;
  Eigen::VectorXd gradient() const override;
  const Eigen::SparseMatrix<double>& hessian() override;
  Eigen::VectorXd gradient_weights() const override { return Eigen::VectorXd::Ones(size()); }
  Eigen::VectorXd mass() const override { return Eigen::VectorXd::Ones(size()); }

  long invalid_encounters() const { return invalid_; }

 private:
  bool valid(const Eigen::VectorXd& x) const;

  Eigen::VectorXd x_;
  InvalidBehaviour behaviour_;
  double invalid_below_;
  Eigen::SparseMatrix<double> hessian_;
  mutable long invalid_ = 0;
};

// E = sum_i sqrt(1 + x_i^2) - f x_i with f > 1: convex (Hessian
// (1 + x_i^2)^(-3/2) > 0) but unbounded below, its gradient tending to
// 1 - f as x_i grows: a motion downhill that never ends. Starts at 0.
class Slope : public Objective {
 public:
  Slope(int n, double f) : f_(f), x_(Eigen::VectorXd::Zero(n)), hessian_(n, n) {
    for (int i = 0; i < n; ++i) hessian_.insert(i, i) = 1.0;
    hessian_.makeCompressed();
  }
  Eigen::Index size() const override { return x_.size(); }
  Eigen::VectorXd get() const override { return x_; }
  void set(const Eigen::VectorXd& q) override { x_ = q; }
  double energy() const override {
    return ((1.0 + x_.array().square()).sqrt() - f_ * x_.array()).sum();
  }
  Eigen::VectorXd gradient() const override {
    return (x_.array() / (1.0 + x_.array().square()).sqrt() - f_).matrix();
  }
  const Eigen::SparseMatrix<double>& hessian() override {
    for (Eigen::Index i = 0; i < x_.size(); ++i)
      hessian_.coeffRef(i, i) = std::pow(1.0 + x_[i] * x_[i], -1.5);
    return hessian_;
  }
  Eigen::VectorXd gradient_weights() const override { return Eigen::VectorXd::Ones(x_.size()); }
  Eigen::VectorXd mass() const override { return Eigen::VectorXd::Ones(x_.size()); }

 private:
  double f_;
  Eigen::VectorXd x_;
  Eigen::SparseMatrix<double> hessian_;
};

// E = 1/2 q'Kq - f.q with a dense symmetric K (stored sparse).
class Quadratic : public Objective {
 public:
  Quadratic(const Eigen::MatrixXd& K, const Eigen::VectorXd& f)
      : K_(K.sparseView()), f_(f), q_(Eigen::VectorXd::Zero(f.size())) {}
  Eigen::Index size() const override { return f_.size(); }
  Eigen::VectorXd get() const override { return q_; }
  void set(const Eigen::VectorXd& q) override { q_ = q; }
  double energy() const override { return 0.5 * q_.dot(K_ * q_) - f_.dot(q_); }
  Eigen::VectorXd gradient() const override { return K_ * q_ - f_; }
  const Eigen::SparseMatrix<double>& hessian() override { return K_; }
  Eigen::VectorXd gradient_weights() const override { return Eigen::VectorXd::Ones(size()); }
  Eigen::VectorXd mass() const override { return Eigen::VectorXd::Ones(size()); }

 private:
  Eigen::SparseMatrix<double> K_;
  Eigen::VectorXd f_, q_;
};

// Callbacks that push the 2-norm of every step a solver takes on
// `objective` into `steps`.
inline NewtonCallbacks recording_step_lengths(const Objective& objective,
                                              std::vector<double>& steps) {
  NewtonCallbacks callbacks;
  callbacks.on_iteration = [&objective, &steps,
                            last = objective.get()](const NewtonReport& report) mutable {
    if (report.iteration > 0) steps.push_back((objective.get() - last).norm());
    last = objective.get();
  };
  return callbacks;
}

}  // namespace xshell::test
