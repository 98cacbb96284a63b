// The damping of solve_dynamics from a Hessian and the masses: C = c M
// (DampingModel::MassProportional), or Rayleigh C = b (H + mu M) with b and
// mu from the lowest eigenvalues (mass_and_damping.hpp), mu making H + mu M
// positive definite near a saddle (see DynamicsOptions).
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "integrators/dynamics/ida_dynamics.hpp"
#include "integrators/dynamics/mass_and_damping.hpp"
#include "integrators/linear_algebra/cholesky_solver.hpp"

namespace xshell {

struct DampingChoice {
  Damping damping;
  double c = 0.0;  // reported
  long factorizations = 0;
  bool unstable = false;   // the Hessian was indefinite
  bool zero_mode = false;  // or had a (numerically) zero mode
  ModeEstimate modes;
};

// warm: the modes of an earlier choice, to start the inverse iterations from.
DampingChoice choose_damping(const DynamicsOptions& options, CholeskySolver& solver,
                             const Eigen::SparseMatrix<double>& H, const Eigen::VectorXd& mass,
                             const ModeEstimate* warm = nullptr);

}  // namespace xshell
