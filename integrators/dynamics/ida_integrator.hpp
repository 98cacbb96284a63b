// IDA as solve_dynamics drives it: the integrator and everything it owns,
// set up from DynamicsOptions; what a failed IDASolve means for the run;
// and the scales and first-step estimate its error control needs.
//
// The unknowns y are [q; v] (second order) or q (first order), see
// ida_system.hpp; q has n = system.unknowns() entries.
#pragma once

#include <Eigen/Core>
#include <string>

#include "integrators/common/objective_evaluator.hpp"
#include "integrators/dynamics/ida_dynamics.hpp"
#include "integrators/dynamics/ida_system.hpp"
#include "integrators/linear_algebra/sundials_handles.hpp"

namespace xshell {

// IDA and everything it owns; declaration order = construction order, the
// context first so that it is destroyed last. The DynamicsSystem (the
// linear solver's backend) must outlive this object.
struct IdaIntegrator {
  SunContext context;
  NVector y, yp, atol, id;
  SunMatrix placeholder;
  SunLinearSolver linear_solver;
  IdaMemory ida;
  std::string last_message;

  // y0, yp0, absolute_tolerances: size system.size().
  IdaIntegrator(DynamicsSystem& system, const DynamicsOptions& options, const Eigen::VectorXd& y0,
                const Eigen::VectorXd& yp0, const Eigen::VectorXd& absolute_tolerances);
};

// The status and reason of a run whose IDASolve returned flag < 0 (throws
// for flags that mean a programming error). message: IDA's last message.
void classify_failure(int flag, const ObjectiveEvaluator& evaluator, const DynamicsSystem& system,
                      const std::string& message, DynamicsResult& result);

// Dimensionless size of a unit of every unknown: the gradient weights have
// the unknowns' units over an energy, so w_i / min_j w_j is 1 for the
// unknowns measured in the smallest units (angles for the linkage) and the
// length scale for the others (positions). Tolerances and the rebase
// distance are multiples of it.
Eigen::VectorXd unknown_scales(const Eigen::VectorXd& weights);

// A first step for IDA from y and y' (atol: IDA's absolute tolerances, rtol
// its relative one). IDA's own estimate is 0.5 / |y'|, over the components
// in the error test; with the velocities out of it (second order,
// q_only), that norm sees only q' = v, which is zero at rest. The step is
// then sized from the motion of q: v h and a h^2 / 2 (a = v') half the
// error test's tolerance. 0: no estimate.
double first_step(const Eigen::Ref<const Eigen::VectorXd>& y,
                  const Eigen::Ref<const Eigen::VectorXd>& yp,
                  const Eigen::Ref<const Eigen::VectorXd>& atol, double rtol, Eigen::Index n,
                  bool q_only);

}  // namespace xshell
