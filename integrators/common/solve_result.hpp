// The outcome of a solve, in one vocabulary for every solver: Newton
// (newton.hpp), constrained Newton and deployment (deployment/), damped
// dynamics (ida_dynamics.hpp) and kinetic damping (kinetic_damping.hpp).
//
// Every solver returns a SolveResult or a struct derived from it that adds
// what only that solver knows (inheritance, so that a solver-agnostic caller
// such as the command line's runners reads any of them as a SolveResult):
//   NewtonResult             = SolveResult (Newton adds nothing)
//   ConstrainedNewtonResult  + multiplier, constraint residual, step kinds
//   DynamicsResult           + simulated time, kinetic energy, IDA counters
//   KineticDampingResult     + resets, mass safety, kinetic energy, counters
//   DeploymentResult         + the accepted steps, failed attempts
//
// No per-iteration history is kept here: each solver reports its
// iterations through a callback with its own report (NewtonReport,
// DynamicsReport, KineticDampingReport, DeploymentStep), because what an
// iteration is differs (a Newton step with its shift and factorizations, a
// time step with its BDF order, a leapfrog step with its resets), and a
// caller keeps what it needs: kinetic damping runs up to a million
// iterations, of which the command line's summary keeps one in a hundred.
#pragma once

#include <atomic>
#include <string>
#include <vector>

namespace xshell {

enum class SolveStatus {
  Converged,             // the convergence test passed (a deployment: every step converged)
  IterationLimit,        // the iteration or time-step limit was reached
  LinearSolverFailed,    // a matrix could not be factorized (even shifted), or gave no solution
  LineSearchFailed,      // no acceptable step, stagnation at the round-off floor, or the
                         // objective rejected every trial point (Newton)
  IntegratorFailed,      // other failures of the time integrator (IDA's error test,
                         // convergence, stagnating steps; dynamics and kinetic damping:
                         // no progress beyond round-off, progress_watch.hpp)
  InvalidConfiguration,  // steps kept leaving the valid configurations (kinetic damping)
  NonFinite,             // NaN/inf in the energy, gradient or Hessian
  Interrupted,           // the stop flag was raised
  StepFailed,            // a deployment step failed even after halving its increment
  Diverged,              // the motion only sped up, downhill, away from any equilibrium
                         // (dynamics, kinetic damping: progress_watch.hpp)
};

// The status as summary.json names it: "converged", "max_iterations",
// "linear_solver_failed", "line_search_failed", "integrator_failed",
// "invalid_configuration", "non_finite", "interrupted", "step_failed", "diverged".
// These names are an interface of the command line: never change them. (A
// converged deployment is "completed" in the summary's "deployment" object
// and in its reason: app/deploy_run.cpp.)
const char* to_string(SolveStatus status);

// The status in words, for messages and reasons: "converged", "maximum
// number of iterations reached", "linear solver failed", "line search
// failed", "integrator failed", "invalid configurations", "non-finite
// values", "interrupted", "step failed", "diverging".
const char* describe(SolveStatus status);

// A saddle that a solver left downhill (integrators/stability/saddle_escape.hpp).
struct SaddleRecord {
  double energy = 0.0;             // total energy at the saddle
  double lowest_eigenvalue = 0.0;  // lambda_min of H phi = lambda M phi there (1/time^2)
  int step = -1;                   // the deployment step being solved (-1: not a deployment)
};

struct SolveResult {
  SolveStatus status = SolveStatus::IterationLimit;
  std::string reason;             // one line
  long iterations = 0;            // completed iterations: Newton iterations (a failed one is not
                                  // counted), time steps (dynamics, end game included), leapfrog
                                  // steps, or all solver iterations of a deployment
  double energy = 0.0;            // at the final state
  double gradient_measure = 0.0;  // max_i |w_i g_i| at the final state (dimensionless)
  bool stable = false;            // an unshifted LL^T of the final (constrained) Hessian succeeded
  long factorizations = 0;  // numeric Cholesky factorizations, the final stability check included
  // Newton's chord corrections (steps with an iteration's factorization,
  // NewtonOptions::max_chord_corrections), not counted in iterations.
  long chord_corrections = 0;
  double setup_seconds = 0.0;  // wall time before the first iteration (0 where not measured:
                               // dynamics, kinetic damping, deployment)
  double seconds = 0.0;        // wall time of the whole solve, setup included
  // Saddles the solve converged to and left along negative curvature, in
  // order (empty when it met none, or with the escape switched off).
  std::vector<SaddleRecord> saddles_escaped;
  bool converged() const { return status == SolveStatus::Converged; }
};

// A number in a reason: "%.3e".
std::string scientific(double value);

// The result of a solve with no free unknowns: converged ("no free
// unknowns"), stable, at the given energy.
void set_no_unknowns(double energy, SolveResult& result);

// The tests that end an iterative solve before its next iteration, in this
// order: stop flag raised (Interrupted, "stop flag raised"), then the limit
// reached (IterationLimit, "no convergence in N <unit>", unit "iterations"
// or "steps"). Sets result.status and result.reason and returns true when
// the solve must end; returns false, leaving result alone, otherwise.
bool stop_or_limit(const std::atomic<bool>* stop, long iterations, long limit, const char* unit,
                   SolveResult& result);

}  // namespace xshell
