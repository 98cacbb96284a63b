// One run of solve_dynamics (ida_dynamics.hpp): the state of the damped
// dynamics between IDA's steps, and the run's phases as methods. A run
// sets up the mass and damping from the starting Hessian, starts at rest or
// on the slow manifold, creates IDA, steps it (rejecting steps that raise
// E + K or end in invalid configurations, refreshing the damping and
// rebasing the objective along the way), hands over to the end game
// (ida_endgame.hpp), and reports. solve_dynamics is the entry point; this
// class is its implementation, declared apart to document its state.
#pragma once

#include <Eigen/Core>
#include <limits>
#include <optional>
#include <string>

#include "integrators/common/objective.hpp"
#include "integrators/common/objective_evaluator.hpp"
#include "integrators/common/wall_clock.hpp"
#include "integrators/dynamics/damping_choice.hpp"
#include "integrators/dynamics/ida_dynamics.hpp"
#include "integrators/dynamics/ida_integrator.hpp"
#include "integrators/dynamics/ida_step_cap.hpp"
#include "integrators/dynamics/ida_system.hpp"
#include "integrators/linear_algebra/cholesky_solver.hpp"

namespace xshell {

// Members are named as a procedure names its variables (as in
// NewtonSolver::Impl): the methods read as the steps of one algorithm.
class DynamicsRun {
 public:
  // The objective must have free unknowns (size() > 0); started: when the
  // run began, for result.seconds.
  DynamicsRun(Objective& target, const DynamicsOptions& run_options,
              const DynamicsCallbacks& run_callbacks, Clock::time_point started);

  // Integrates until convergence or failure; call once.
  DynamicsResult solve();

 private:
  // Set-up.
  DynamicsSystem set_up_mass_and_damping();
  void set_up_state();
  void start_on_slow_manifold();
  // IDA.
  void integrate();
  void create_integrator();
  bool advance();
  bool take_step(double h);
  void on_integrator_failure(int flag);
  bool step_is_sound(double h);
  bool stops_here();
  bool settled_in_stable_basin(bool at_rest);
  // Along the motion.
  void refresh_by_distance(double h);
  void rebase_if_due(double h);
  Damping refreshed_damping();
  void restart_at(double time, double h_first);
  bool retry_shorter(double h, const std::string& why);
  // The end.
  bool play_endgame();
  void finish(SolveStatus status, std::string reason);
  DynamicsResult final_result();
  // Helpers.
  double kinetic(const Eigen::VectorXd& state) const;
  Eigen::VectorXd absolute_tolerances() const;
  void accumulate_stats();

  Objective& objective;                // moved along the run; left at the last accepted state
  const DynamicsOptions& options;      // as given
  const DynamicsCallbacks& callbacks;  // as given
  const Clock::time_point start;       // when the run began
  const Eigen::Index n;                // free unknowns (size of q)
  const bool second_order;             // y = [q; v] (else y = q)
  DynamicsResult result;               // filled along the run
  ObjectiveEvaluator evaluator;        // the objective as IDA's callbacks see it
  CholeskySolver estimator;            // factorizations outside IDA: modes, definiteness checks
  Eigen::VectorXd mass;                // M, diagonal, size n
  DampingChoice choice;                // C, and the modes it came from
  long extra_factorizations = 0;       // the end games' factorizations
  std::optional<bool> endgame_stable;  // a converged end game's stability test, at the final state
  DynamicsSystem system;          // what IDA integrates (after mass and choice: built from them)
  Eigen::VectorXd y;              // the state, [q; v] or q
  Eigen::VectorXd weights;        // gradient weights (change at rebases)
  Eigen::VectorXd scales;         // unknown_scales of the start's weights (or ones)
  double energy0 = 0.0;           // E at the start
  DynamicsReport report;          // of the last accepted step (or the start)
  bool on_slow_manifold = false;  // the start velocity is set (not at rest)
  std::optional<IdaIntegrator> integrator;  // after system, which must outlive it
  std::optional<ProgressWatch> watch;       // divergence and stagnation, from the start
  bool q_only = false;                      // velocities out of IDA's error test
  double time_scale = 1.0;                  // 1 / rate of the slowest damped mode
  double total0 = 0.0;                      // E + K at the start
  double last_total = 0.0;                  // E + K at last_good
  Eigen::VectorXd last_good;                // the last accepted state
  double last_good_t = 0.0;                 // its time
  double t = 0.0;                           // IDA's time
  Eigen::VectorXd rebased_at;               // q at the last rebase
  Eigen::VectorXd refreshed_at;             // q at the last damping refresh
  long last_rebase = 0;                     // step of the last rebase
  bool endgame = false;                     // the dynamics hand over to the end game
  // After a K that was not positive definite, steps as long are not tried
  // again for a while (ida_step_cap.hpp). The cap is set as the
  // factorization fails, so that IDA's next step obeys it.
  DefiniteStepCap step_cap;
  // An end game that does not converge hands back to the dynamics, which
  // then waits for steps endgame.growth times longer, or a gradient
  // endgame.growth times smaller, before the next (both triggers back off).
  double endgame_backoff = 1.0;
  // The at-rest end game (EndgameOptions::rest_check_fall) waits for a
  // gradient measure below this: after a check that found H indefinite, a
  // fraction of the measure there; after an end game that did not
  // converge, its start's measure over endgame.growth.
  double rest_check_below = std::numeric_limits<double>::infinity();
  bool endgame_on = false;  // options.endgame.step_length > 0
};

}  // namespace xshell
