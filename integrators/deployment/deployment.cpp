#include "integrators/deployment/deployment.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <functional>
#include <memory>
#include <optional>
#include <stdexcept>

#include "integrators/common/linkage_objective.hpp"
#include "integrators/common/wall_clock.hpp"
#include "integrators/deployment/average_constraint.hpp"
#include "integrators/deployment/constrained_newton.hpp"
#include "integrators/deployment/constrained_objective.hpp"
#include "integrators/deployment/joint_charts.hpp"
#include "integrators/deployment/path_predictor.hpp"
#include "integrators/deployment/predicted_start.hpp"
#include "integrators/deployment/step_control.hpp"
#include "integrators/stability/branch_bias.hpp"
#include "linkage/frame_free_unknowns.hpp"
#include "linkage/opening_angle_range.hpp"

namespace xshell {

namespace {

// Step of the central difference in the prescribed angles (radians): the
// truncation error h^2 E''' / 6 and the round-off eps E / h are both near
// 1e-10 relative.
constexpr double kTorqueStep = 1e-5;

// Step of the gradient's central second difference along the path's
// tangent (radians of the average opening angle): the truncation error is
// O(1e-6) relative, the round-off eps |g| / 1e-6, about 1e-10 |g|.
constexpr double kCurvatureStep = 1e-3;

// The constrained Newton of a deployment's steps: its step cap grows
// (NewtonOptions::grow_step_cap), for the snap-throughs whose descent takes
// tens of capped steps in a row (docs/model.md 9.3).
NewtonOptions step_newton(NewtonOptions options) {
  options.grow_step_cap = true;
  return options;
}

// The outcome of one solve, whichever solver ran it.
struct Attempt {
  SolveResult solve;
  double torque = 0.0;              // dE/dA or dE/dtheta
  bool at_round_off_floor = false;  // ConstrainedNewtonResult's
};

struct Twin;

// Deploys one problem: the state of a run of deploy().
class Deployer {
 public:
  Deployer(LinkageProblem& problem, const DeploymentPlan& plan, const DeploymentOptions& options,
           const DeploymentCallbacks& callbacks)
      : problem_(problem),
        plan_(plan),
        options_(options),
        callbacks_(callbacks),
        objective_(problem) {
    if (plan.steps < 1) throw std::invalid_argument("deployment: steps must be at least 1");
    const RodLinkage& linkage = problem.linkage();
    if (plan.joint_angles.empty()) {
      constraint_.emplace(average_opening_angle_constraint(problem));
      start_average_ = constraint_->value(problem.free_dofs());
    } else {
      const std::vector<int>& free = problem.free_indices();
      for (const PrescribedAngle& p : plan.joint_angles) {
        if (p.joint < 0 || p.joint >= linkage.num_joints())
          throw std::invalid_argument("deployment: joint " + std::to_string(p.joint) +
                                      " out of range");
        const int r = linkage.joint_dof_offset(p.joint) + kAlpha;
        if (std::binary_search(free.begin(), free.end(), r))
          throw std::invalid_argument(
              "deployment: the opening angle of joint " + std::to_string(p.joint) +
              " is prescribed but free: fix it with an opening_angle support");
        alpha_index_.push_back(r);
        start_angles_.push_back(linkage.joint(p.joint).opening_angle());
      }
    }
    // The user's branch: saddles are left on its side (dynamics under the
    // average constraint sees the null-space coordinates z).
    const Eigen::VectorXd bias = branch_bias(problem, options.buckling_direction);
    options_.newton.escape.bias = bias;
    options_.dynamics.escape.bias = constraint_ ? constraint_->restrict(bias) : bias;
    // The constrained Newton solver also computes the tangent predictor.
    if (constraint_ && (options.solver == DeploymentSolver::Newton ||
                        options.predictor != DeploymentPredictor::UniformShift))
      constrained_newton_ = std::make_unique<ConstrainedNewtonSolver>(objective_, *constraint_,
                                                                      step_newton(options_.newton));
    if (!constraint_ && options.solver == DeploymentSolver::Newton)
      newton_ = std::make_unique<NewtonSolver>(objective_, options_.newton);
    const std::vector<bool> frame_free = frame_free_unknowns(linkage);
    for (int r : problem.free_indices()) comparable_.push_back(frame_free[r]);
    chart_free_ = comparable_;
    // Their omegas are compared in one chart (joint_charts.hpp).
    rotations_ = free_rotations(problem);
    for (const FreeRotation& r : rotations_)
      for (int i : r.free) comparable_[i] = true;
    start_twin();
  }
  ~Deployer();

  DeploymentResult run() {
    const Clock::time_point start = Clock::now();
    result_.start_angle = average_opening_angle(problem_.linkage());

    // Step 0: equilibrium at the start's own value.
    if (!advance(0.0, 0, 0)) return finish(start);

    StepControl control(plan_.steps, largest_increment());
    int step = 0, halvings = 0;
    double failed_seconds = 0.0;
    while (!control.done()) {
      const double target = control.next();
      const Clock::time_point attempt_start = Clock::now();
      if (advance(target, step + 1, halvings, failed_seconds)) {
        ++step;
        halvings = 0;
        failed_seconds = 0.0;
        const DeploymentStep& row = result_.steps.back();
        control.accepted(row.iterations,
                         row.saddles_escaped > 0 || result_.branch_switch_step == step);
        continue;
      }
      if (result_.status == SolveStatus::Interrupted) break;
      if (halvings >= options_.max_halvings) {
        char text[160];
        std::snprintf(text, sizeof text,
                      "the step to s = %.6g (average opening angle %.6g rad) failed %d times: ",
                      target, average_target(target), halvings + 1);
        result_.reason = text + last_reason_;
        break;
      }
      ++halvings;
      failed_seconds += seconds_since(attempt_start);
      control.failed();
    }
    if (control.done()) {
      result_.status = SolveStatus::Converged;
      result_.reason = "reached the target in " + std::to_string(step) + " steps";
    }
    return finish(start);
  }

 private:
  // DeploymentPlan::largest_step as an increment of s (0: none).
  double largest_increment() const {
    if (!(plan_.largest_step > 0.0)) return 0.0;
    double span = std::abs(plan_.average_angle - start_average_);
    if (!constraint_) {
      span = 0.0;
      for (size_t k = 0; k < start_angles_.size(); ++k)
        span = std::max(span, std::abs(plan_.joint_angles[k].angle - start_angles_[k]));
    }
    return span > 0.0 ? plan_.largest_step / span : 0.0;
  }

  double average_target(double s) const {
    if (!constraint_) return average_opening_angle(problem_.linkage());
    return start_average_ + s * (plan_.average_angle - start_average_);
  }

  // Sets the actuated unknowns for path parameter s.
  void apply(double s) {
    if (constraint_) {
      const Eigen::VectorXd q = problem_.free_dofs();
      const double target = average_target(s);
      const double change = target - constraint_->value(q);
      if (options_.predictor != DeploymentPredictor::UniformShift && change != 0.0) {
        const Eigen::VectorXd t = constrained_newton_->tangent();
        if (t.size() == q.size() && t.allFinite()) {
          if (!path_.empty()) path_.back().tangent = t;  // for the next step's cubic
          if (predict(q, t, change, target)) return;
          problem_.set_free_dofs(q);
        }
      }
      Eigen::VectorXd shifted = q;
      constraint_->project(shifted, target);
      problem_.set_free_dofs(shifted);
      return;
    }
    Eigen::VectorXd r = problem_.dofs();
    for (size_t k = 0; k < alpha_index_.size(); ++k)
      r[alpha_index_[k]] = start_angles_[k] + s * (plan_.joint_angles[k].angle - start_angles_[k]);
    problem_.set_dofs(r);
  }

  // Moves to the tangent's prediction q + change t for the average
  // `target`, or with the quadratic predictor to the curved prediction of
  // lowest energy, the tangent's included (predicted_start.hpp). False when
  // the problem rejected every prediction.
  bool predict(const Eigen::VectorXd& q, const Eigen::VectorXd& t, double change, double target) {
    Eigen::VectorXd linear = q + change * t;
    constraint_->project(linear, target);  // round-off only: a . t = 1
    std::vector<Eigen::VectorXd> starts;
    if (options_.predictor == DeploymentPredictor::Quadratic)
      starts = curved_predictions(q, t, linear, change, target);
    starts.push_back(std::move(linear));
    if (starts.size() == 1) {  // no choice, no energy to compare
      try {
        problem_.set_free_dofs(starts.front());
        return true;
      } catch (const std::domain_error&) {
        return false;
      }
    }
    const PredictedStart start = lowest_energy_start(problem_, starts);
    if (start.index > 0 && start.index + 1 == static_cast<int>(starts.size()))
      ++result_.curvature_dropped;
    return start.index >= 0;
  }

  // The curved predictions from q (path_predictor.hpp), none before the
  // last two equilibria lie on one path: the cubic (Hermite) through them,
  // then, when the path's second derivative could be found (kept at q for
  // the next step), the Taylor cubic, the Hermite polynomial with it (a
  // quintic once the equilibrium before has its own) and the Taylor
  // polynomial. (From the Taylor polynomial alone, at
  // the first step and after a jump, the benchmark's deployments took more
  // iterations: darth_vader 123 against 105.)
  std::vector<Eigen::VectorXd> curved_predictions(const Eigen::VectorXd& q,
                                                  const Eigen::VectorXd& t,
                                                  const Eigen::VectorXd& linear, double change,
                                                  double target) {
    if (path_.size() != 2) return {};
    const PathPoint previous = in_current_charts(path_[0], problem_.linkage(), rotations_);
    std::vector<Eigen::VectorXd> out{
        linear + path_curvature_step(previous, path_[1], t, change, comparable_)};
    const Eigen::VectorXd k = path_second_derivative(q, t);
    if (k.size() == q.size()) {
      path_.back().curvature = k;
      out.push_back(linear + taylor_cubic_step(previous, path_[1], t, k, change, comparable_));
      out.push_back(
          linear + hermite_taylor_step(previous, path_[1], t, k, change, comparable_, chart_free_));
      out.push_back(linear + 0.5 * change * change * k);
    }
    for (Eigen::VectorXd& start : out) constraint_->project(start, target);
    return out;
  }

  // q'' at the equilibrium q, whose path tangent is t (the last tangent()):
  // D3E[t, t] by the gradient's central second difference, then
  // ConstrainedNewtonSolver::second_derivative. Empty when a point of the
  // difference is rejected or a value is not finite. Leaves the problem at q.
  Eigen::VectorXd path_second_derivative(const Eigen::VectorXd& q, const Eigen::VectorXd& t) {
    const Eigen::VectorXd third = gradient_second_difference_or_empty(
        [&](const Eigen::VectorXd& x) {
          problem_.set_free_dofs(x);
          return problem_.free_gradient();
        },
        q, t, kCurvatureStep);
    if (third.size() == 0) return {};
    const Eigen::VectorXd k = constrained_newton_->second_derivative(third);
    return k.allFinite() ? k : Eigen::VectorXd();
  }

  // Solves at s; `abandon`, when given, is asked after every iteration (or
  // time step) and stops the solve (as interrupted) when it says so.
  Attempt solve(double s, const std::function<bool()>& abandon = {}) {
    Attempt a;
    std::atomic<bool> stop{false};
    const auto check = [&] {
      if ((callbacks_.stop && *callbacks_.stop) || (abandon && abandon())) stop = true;
    };
    NewtonCallbacks newton_callbacks;
    newton_callbacks.on_iteration = [&](const NewtonReport& report) {
      if (callbacks_.on_newton_iteration) callbacks_.on_newton_iteration(report);
      check();
    };
    newton_callbacks.stop = abandon ? &stop : callbacks_.stop;
    DynamicsCallbacks dynamics_callbacks;
    dynamics_callbacks.on_step = [&](const DynamicsReport& report) {
      if (callbacks_.on_dynamics_step) callbacks_.on_dynamics_step(report);
      check();
    };
    dynamics_callbacks.stop = abandon ? &stop : callbacks_.stop;
    if (constrained_newton_ && options_.solver == DeploymentSolver::Newton) {
      const ConstrainedNewtonResult r =
          constrained_newton_->solve(average_target(s), newton_callbacks);
      a = {r, r.multiplier, r.at_round_off_floor};
    } else if (newton_) {
      a.solve = newton_->solve(newton_callbacks);
    } else if (constraint_) {
      ConstrainedObjective reduced(objective_, *constraint_);
      a.solve = solve_dynamics(reduced, options_.dynamics, dynamics_callbacks);
      a.torque = reduced.multiplier();
    } else {
      a.solve = solve_dynamics(objective_, options_.dynamics, dynamics_callbacks);
    }
    if (!constraint_) a.torque = prescribed_torque();
    return a;
  }

  // solve(s), by Newton within DeploymentOptions::step_iterations for the
  // first attempt at every step but the start: a step that has not
  // converged by then fails and is halved, and its retries keep Newton's
  // own limit (a fold of the path, where any increment needs a long
  // descent, is still crossed).
  Attempt solve_within_budget(double s, int step, int halvings) {
    const long budget = options_.step_iterations;
    if (budget <= 0 || step == 0 || halvings > 0 || options_.max_halvings == 0 ||
        options_.solver != DeploymentSolver::Newton)
      return solve(s);
    long reports = 0;  // the start's included
    bool over = false;
    Attempt a = solve(s, [&] { return over = ++reports > budget; });
    const bool stopped = callbacks_.stop && callbacks_.stop->load();
    if (over && a.solve.status == SolveStatus::Interrupted && !stopped) {
      a.solve.status = SolveStatus::IterationLimit;
      a.solve.reason = "no equilibrium within the step's " + std::to_string(budget) +
                       " iterations (DeploymentOptions::step_iterations)";
    }
    return a;
  }

  // dE/dtheta along the prescribed path (see the header), by a central
  // difference in the prescribed angles at the current equilibrium.
  double prescribed_torque() {
    Eigen::VectorXd direction(alpha_index_.size());
    for (size_t k = 0; k < alpha_index_.size(); ++k)
      direction[k] = plan_.joint_angles[k].angle - start_angles_[k];
    const double mean = direction.mean();
    if (std::abs(mean) > 1e-12)
      direction /= mean;
    else
      direction.setOnes();
    const Eigen::VectorXd r = problem_.dofs();
    auto energy_at = [&](double h) {
      Eigen::VectorXd shifted = r;
      for (size_t k = 0; k < alpha_index_.size(); ++k) shifted[alpha_index_[k]] += h * direction[k];
      problem_.set_dofs(shifted);
      return problem_.energy().total();
    };
    const double torque = (energy_at(kTorqueStep) - energy_at(-kTorqueStep)) / (2.0 * kTorqueStep);
    problem_.set_dofs(r);
    return torque;
  }

  // Moves to s and solves; on success records the step, otherwise restores
  // the last accepted state.
  bool advance(double s, int step, int halvings, double earlier_seconds = 0.0) {
    const Clock::time_point start = Clock::now();
    const LinkageProblem saved = problem_;
    Attempt a;
    long predictor_factorizations = 0;  // of the tangent
    try {
      const long before = constrained_newton_ ? constrained_newton_->factorizations() : 0;
      apply(s);
      if (constrained_newton_)
        predictor_factorizations = constrained_newton_->factorizations() - before;
      a = solve_within_budget(s, step, halvings);
    } catch (const std::domain_error& e) {
      a = Attempt{};
      a.solve.reason = e.what();
    }
    a.solve.factorizations += predictor_factorizations;
    result_.iterations += a.solve.iterations;
    result_.factorizations += a.solve.factorizations;
    result_.chord_corrections += a.solve.chord_corrections;
    if (!a.solve.converged()) {
      problem_ = saved;
      last_reason_ = a.solve.reason;
      if (a.solve.status == SolveStatus::Interrupted) {
        result_.status = SolveStatus::Interrupted;
        result_.reason = "interrupted at step " + std::to_string(step);
      } else {
        ++result_.failed_attempts;
        result_.status = SolveStatus::StepFailed;
        if (step == 0)
          result_.reason = "the start could not be brought to equilibrium: " + a.solve.reason;
      }
      return false;
    }
    if (twin_) prefer_user_branch(s, step, a);
    record(s, step, halvings, a, earlier_seconds + seconds_since(start));
    return true;
  }

  // Appends an accepted step's row and reports it.
  void record(double s, int step, int halvings, const Attempt& a, double seconds) {
    DeploymentStep row;
    row.step = step;
    row.fraction = s;
    row.average_angle = average_opening_angle(problem_.linkage());
    const OpeningAngleRange range = opening_angle_range(problem_.linkage());
    row.min_opening_angle = range.min.value_or(0.0);
    row.max_opening_angle = range.max.value_or(0.0);
    row.outside_opening_range = static_cast<int>(range.outside.size());
    row.energy = problem_.energy();
    row.torque = a.torque;
    row.iterations = a.solve.iterations;
    row.factorizations = a.solve.factorizations;
    row.stable = a.solve.stable;
    row.saddles_escaped = static_cast<int>(a.solve.saddles_escaped.size());
    for (SaddleRecord saddle : a.solve.saddles_escaped) {
      saddle.step = step;
      result_.saddles_escaped.push_back(saddle);
    }
    row.gradient_measure = a.solve.gradient_measure;
    if (a.at_round_off_floor) ++result_.round_off_floor_steps;
    row.halvings = halvings;
    row.seconds = seconds;
    result_.steps.push_back(row);
    remember_path_point(step, a);
    if (callbacks_.on_step) callbacks_.on_step(row);
  }

  // Keeps the accepted equilibrium for the quadratic predictor; a saddle
  // left in this step, or a branch taken from the twin, jumped off the path
  // its predecessor was on.
  void remember_path_point(int step, const Attempt& a) {
    if (!constraint_) return;
    const bool jumped = !a.solve.saddles_escaped.empty() || result_.branch_switch_step == step;
    if (jumped) path_.clear();
    if (path_.size() == 2) path_.erase(path_.begin());
    const Eigen::VectorXd q = problem_.free_dofs();
    path_.push_back({q, constraint_->value(q), {}, joint_frames(problem_.linkage(), rotations_)});
  }

  // The branch choice under loads (DeploymentOptions::follow_unloaded_twin).
  void start_twin();
  void prefer_user_branch(double s, int step, Attempt& a);
  void end_twin();

  // The final state: the last accepted step's, or the start's.
  DeploymentResult finish(Clock::time_point start) {
    if (twin_) end_twin();
    if (result_.steps.empty()) {
      result_.energy = problem_.energy().total();
      result_.gradient_measure = problem_.gradient_measure();
    } else {
      const DeploymentStep& last = result_.steps.back();
      result_.energy = last.energy.total();
      result_.gradient_measure = last.gradient_measure;
      result_.stable = last.stable;
    }
    result_.seconds = seconds_since(start);
    return std::move(result_);
  }

  LinkageProblem& problem_;
  const DeploymentPlan& plan_;
  DeploymentOptions options_;  // with the branch bias of this problem
  const DeploymentCallbacks& callbacks_;
  LinkageObjective objective_;
  std::optional<AverageConstraint> constraint_;
  double start_average_ = 0.0;
  std::vector<int> alpha_index_;      // reduced index of each prescribed alpha
  std::vector<double> start_angles_;  // their values at the start
  std::unique_ptr<ConstrainedNewtonSolver> constrained_newton_;
  std::unique_ptr<NewtonSolver> newton_;
  DeploymentResult result_;
  std::string last_reason_;
  std::unique_ptr<Twin> twin_;    // while the branch choice follows it
  std::vector<PathPoint> path_;   // the last (at most two) equilibria of the path
  std::vector<bool> comparable_;  // per free unknown: frame_free_unknowns(), and rotations_
  std::vector<bool> chart_free_;  // per free unknown: frame_free_unknowns()
  std::vector<FreeRotation> rotations_;
};

// The same problem and plan without the loads' component along the
// buckling direction, deployed beside the loaded one without reporting its
// steps (DeploymentOptions::follow_unloaded_twin).
struct Twin {
  Twin(const LinkageProblem& loaded, const DeploymentPlan& plan, const DeploymentOptions& options,
       const DeploymentCallbacks& main)
      : problem(loaded),
        deployer(symmetric(problem, options.buckling_direction), plan, without_twin(options),
                 quiet(main)) {}

  static LinkageProblem& symmetric(LinkageProblem& p, const Eigen::Vector3d& direction) {
    p.remove_loads_along(direction);
    return p;
  }
  static DeploymentOptions without_twin(DeploymentOptions o) {
    o.follow_unloaded_twin = false;
    return o;
  }
  const DeploymentCallbacks& quiet(const DeploymentCallbacks& main) {
    callbacks.stop = main.stop;
    return callbacks;
  }

  LinkageProblem problem;
  DeploymentCallbacks callbacks;  // the stop flag only
  Deployer deployer;
  // A mean displacement above this (1e-6 of the input's bounding-box
  // diagonal) has left the symmetric state.
  double threshold = 0.0;
};

Deployer::~Deployer() = default;

void Deployer::start_twin() {
  const bool escape = options_.solver == DeploymentSolver::Newton
                          ? options_.newton.escape.enabled
                          : options_.dynamics.escape.enabled;
  if (!options_.follow_unloaded_twin || !escape) return;
  if (!(problem_.load_along(options_.buckling_direction) < 0.0)) return;
  twin_ = std::make_unique<Twin>(problem_, plan_, options_, callbacks_);
  Eigen::AlignedBox3d box;
  for (const Eigen::Vector3d& v : problem_.linkage().graph().vertices) box.extend(v);
  twin_->threshold = 1e-6 * box.diagonal().norm();
}

// When this step's state lies on the loads' side: brings the twin to s and
// solves the loaded problem from the twin's state, and a stable
// equilibrium on the user's side replaces the step's (a and the state) and
// ends the twin.
void Deployer::prefer_user_branch(double s, int step, Attempt& a) {
  const Eigen::Vector3d& direction = options_.buckling_direction;
  // On the user's side already: the twin waits (a later advance catches up
  // in one step, or ends it).
  if (mean_displacement(problem_, direction) >= 0.0) return;
  if (!twin_->deployer.advance(s, step, 0)) {
    end_twin();  // no symmetric state to start from
    return;
  }
  // Until the twin has left its symmetric state it has nothing to offer.
  if (!(mean_displacement(twin_->problem, direction) > twin_->threshold)) return;
  LinkageProblem kept = problem_;
  problem_ = twin_->problem;
  problem_.restore_loads();
  Attempt b;
  const auto heading_to_loads_side = [&] { return mean_displacement(problem_, direction) < 0.0; };
  try {
    b = solve(s, heading_to_loads_side);
  } catch (const std::domain_error& e) {
    b.solve.reason = e.what();
  }
  result_.iterations += b.solve.iterations;
  result_.factorizations += b.solve.factorizations;
  result_.chord_corrections += b.solve.chord_corrections;
  if (b.solve.converged() && b.solve.stable && mean_displacement(problem_, direction) > 0.0) {
    a = std::move(b);
    result_.branch_switch_step = step;
    end_twin();
    return;
  }
  problem_ = std::move(kept);
}

// The twin's work counts in the run's totals.
void Deployer::end_twin() {
  result_.iterations += twin_->deployer.result_.iterations;
  result_.factorizations += twin_->deployer.result_.factorizations;
  result_.chord_corrections += twin_->deployer.result_.chord_corrections;
  twin_.reset();
}

}  // namespace

DeploymentResult deploy(LinkageProblem& problem, const DeploymentPlan& plan,
                        const DeploymentOptions& options, const DeploymentCallbacks& callbacks) {
  return Deployer(problem, plan, options, callbacks).run();
}

}  // namespace xshell
