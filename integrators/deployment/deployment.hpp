// Deployment: opening a linkage from its current state to a target by
// continuation, every step solved to equilibrium.
//
// Actuation, one of:
//  - the average opening angle A over all joints (average_constraint.hpp):
//    each step first shifts every free opening angle by the same amount so
//    that the average is the step's target, then solves
//      Newton:   grad E = tau a, a . q = A by the Schur complement
//                (constrained_newton.hpp);
//      dynamics: the unconstrained dynamics in the constraint's null-space
//                coordinates q = c + B z (constrained_objective.hpp), so that
//                IDA sees no algebraic constraint;
//    the torque tau = dE/dA is the multiplier a.g / a.a of the final
//    gradient (energy per radian, positive when the linkage resists opening);
//  - prescribed opening angles at chosen joints, whose alpha must be fixed
//    unknowns of the problem (an "opening_angle" support): each step sets
//    them on the straight path from their start values to their targets and
//    solves the plain problem (newton.hpp or dynamics.hpp). The torque is
//    dE/dtheta with theta the mean of the prescribed angles along that path
//    (a central difference of the equilibrium energy in the prescribed
//    angles, which by the envelope theorem is the derivative of the
//    equilibrium energy: the sum of the actuation moments weighted by how
//    fast each joint is driven).
//
// Continuation: the path parameter s runs from 0 (the start) to 1 (the
// target) in `steps` equal increments, or in adaptive ones
// (DeploymentPlan::largest_step; step_control.hpp). Step 0 solves at the
// start's own value. A step whose solve fails, or whose first attempt takes
// more than step_iterations Newton iterations, is undone (the problem is
// restored to the last accepted state) and retried with half the increment,
// at most max_halvings times in a row; after a success the increment
// doubles back up to the nominal one, and with equal increments steps
// always land on the nominal grid s = k / steps. Every step's solve checks the stability of its
// equilibrium (on the constraint's tangent space under the average actuation) and, by default,
// leaves a saddle downhill along negative curvature on the side of buckling_direction, so the
// continuation follows the stable branch through a bifurcation (a flat linkage popping out of its
// plane). With the escape off (newton.escape.enabled, dynamics.escape.enabled) saddles are accepted
// and reported as unstable steps.
#pragma once

#include <atomic>
#include <functional>
#include <string>
#include <vector>

#include "integrators/common/solve_result.hpp"
#include "integrators/dynamics/ida_dynamics.hpp"
#include "integrators/newton/newton.hpp"
#include "linkage/statics_problem.hpp"

namespace xshell {

enum class DeploymentSolver { Newton, Dynamics };

// How a step's start is put on the constraint (average actuation).
enum class DeploymentPredictor {
  // Every free opening angle shifted by the same amount: the rods' other
  // unknowns stay behind, so each joint's terminal edges kink against their
  // neighbours and the solver starts far from equilibrium.
  UniformShift,
  // Along the tangent of the equilibrium path at the last accepted step
  // (ConstrainedNewtonSolver::tangent(), one factorization): q + dA t, which
  // meets the constraint exactly (a . t = 1) and starts the solver close to
  // the next equilibrium. Falls back to the uniform shift when no tangent
  // can be computed or the predicted configuration is invalid.
  Tangent,
  // The tangent and the curvature of the path (path_predictor.hpp), the
  // lowest in energy of these starts (predicted_start.hpp; they all meet
  // the constraint):
  //  - the cubic through the last two accepted equilibria with the tangents
  //    at both (the quadratic through them with the last tangent alone
  //    before the earlier tangent is known), on the unknowns that keep
  //    their meaning across the solvers' rebases (positions, opening
  //    angles, edge lengths: linkage/frame_free_unknowns.hpp);
  //  - the Taylor polynomial of degree 2 at the last equilibrium, its
  //    second derivative from the gradient's second difference along the
  //    tangent (two gradients more, no factorization), on every unknown,
  //    and the cubic through the equilibrium before with it;
  //  - the tangent alone.
  // The two-equilibria ones are left out at the first step, and after a
  // step that left a saddle or took the twin's branch (the path jumped
  // there); a snap-through makes the path jump unseen, and the energies
  // then choose. On manta_ray the regular steps converge in 2 Newton
  // iterations, against 3 with the quadratic (docs/model.md 9.3).
  Quadratic,
};

struct PrescribedAngle {
  int joint = 0;       // joint index (not vertex)
  double angle = 0.0;  // target opening angle, radians
};

struct DeploymentPlan {
  // Prescribed angles when non-empty; otherwise the average opening angle
  // is driven to average_angle (radians).
  std::vector<PrescribedAngle> joint_angles;
  double average_angle = 0.0;
  int steps = 20;  // nominal number of increments (>= 1)
  // Adaptive increments (step_control.hpp) when > 0: the largest increment
  // of the actuated angle (radians; of the average, or of the prescribed
  // angle that moves most), reached by doubling 1 / steps of the way after
  // every step that converged in at most two iterations; the number of
  // steps then follows. 0: `steps` equal increments.
  double largest_step = 0.0;
};

struct DeploymentOptions {
  DeploymentSolver solver = DeploymentSolver::Newton;
  DeploymentPredictor predictor = DeploymentPredictor::Quadratic;  // average actuation only
  // line_search is ignored under the average constraint, and there the
  // step cap grows (grow_step_cap set: docs/model.md 9.3).
  NewtonOptions newton;
  DynamicsOptions dynamics;  // per step, from its start (DynamicsOptions::start)
  int max_halvings = 6;      // consecutive halvings of a failing increment
  // Newton iterations the first attempt at a step may take (saddle escapes
  // and the descents from them included) before it fails and the increment
  // is halved; 0: Newton's own limit (newton.max_iterations, counted again
  // from each saddle left). The start (step 0) and the retries keep
  // Newton's limit, so that a fold of the path, past which every increment
  // needs a long descent, is still crossed (bounding the retries too made
  // the largest design's increments shrink without end there). A smaller
  // increment is cheaper than a long struggle: on scary_face, attempts that
  // left a saddle crept for their whole 300 iterations, while their halves
  // converged in 3. Benchmark deployments (bench/deployments.py), Newton
  // iterations: scary_face 1,572 without a budget, 581 with 60, 751 with
  // 100; the largest design 898, 1,304 and 698.
  long step_iterations = 100;
  // The user's branch (branch_bias.hpp): at every step a converged saddle
  // is left (newton.escape, dynamics.escape; their bias is set from this
  // direction) on the side where the vertices' mean displacement along it
  // is positive.
  Eigen::Vector3d buckling_direction = Eigen::Vector3d::UnitZ();
  // Loads that push against buckling_direction (gravity with the default
  // +z) choose the side before the escape can: the linkage sags to their
  // side and never meets a saddle. When this is on, the escape is on and
  // the loads push against the direction, the deployment also follows its
  // twin: the same problem without the loads' component along the
  // direction, which leaves its symmetric state by the escape on the
  // user's side. At every step whose state lies on the loads' side (the
  // vertices' mean displacement along the direction below 0) the twin is
  // brought to the same step (it waits while the state is on the user's
  // side), and once it has left its symmetric state the loaded problem is
  // solved again from the twin's state; the first stable equilibrium so found on the
  // user's side replaces the step, the twin ends, and the continuation
  // follows that branch (docs/model.md section 9.6).
  bool follow_unloaded_twin = true;
};

// One accepted step: one row of deployment.csv.
struct DeploymentStep {
  int step = 0;                // 0: the start; then 1, 2, ... per accepted step
  double fraction = 0.0;       // s, progress from the start (0) to the target (1)
  double average_angle = 0.0;  // mean opening angle over all joints, radians
  // The smallest and largest opening angle of any joint (radians), and how
  // many joints are outside (0, pi) (linkage/opening_angle_range.hpp).
  double min_opening_angle = 0.0, max_opening_angle = 0.0;
  int outside_opening_range = 0;
  EnergyReport energy;
  double torque = 0.0;  // dE/dA (or dE/dtheta for prescribed angles), energy per radian
  long iterations = 0;  // Newton iterations or dynamics time steps of this step
  // Sparse factorizations of this step's predictor (the tangent, when the
  // last step's final one cannot be reused) and of its Newton solve (the
  // dynamics' own are not counted).
  long factorizations = 0;
  bool stable = false;      // unshifted LL^T of the (constrained) Hessian succeeded
  int saddles_escaped = 0;  // saddles this step's solve converged to and left
  double gradient_measure = 0.0;
  int halvings = 0;      // failed attempts before this step was accepted
  double seconds = 0.0;  // wall time of the step, failed attempts included
};

struct DeploymentCallbacks {
  std::function<void(const DeploymentStep&)> on_step;            // after every accepted step
  std::function<void(const NewtonReport&)> on_newton_iteration;  // optional
  std::function<void(const DynamicsReport&)> on_dynamics_step;   // optional
  const std::atomic<bool>* stop = nullptr;                       // checked by the solvers
};

// The common result (solve_result.hpp) of the whole deployment and its
// steps. status: Converged when the target was reached with every step
// converged ("completed"), StepFailed when a step failed even after
// max_halvings halvings, Interrupted when the stop flag was raised.
// iterations: all solver iterations (or time steps), failed attempts
// included; factorizations likewise (where the solver counts them); energy,
// gradient_measure and stable: of the last accepted step (without one, the
// start's energy and gradient measure, not stable).
struct DeploymentResult : SolveResult {
  DeploymentResult() { status = SolveStatus::StepFailed; }
  std::vector<DeploymentStep> steps;  // accepted steps, from step 0
  int failed_attempts = 0;
  // Step attempts (failed ones included) that started from the tangent's
  // prediction because every curved one (DeploymentPredictor::Quadratic)
  // had a higher energy there: after a snap-through, whose two sides no
  // smooth curve joins.
  int curvature_dropped = 0;
  // Accepted steps whose equilibrium stopped at the gradient's round-off
  // floor within twice the tolerance (ConstrainedNewtonResult).
  int round_off_floor_steps = 0;
  // The step at which the loaded branch on the user's side was taken from
  // the unloaded twin (follow_unloaded_twin), -1 when none was.
  int branch_switch_step = -1;
  double start_angle = 0.0;  // average opening angle before step 0
};

// Deploys `problem` from its current state. On failure or interruption the
// problem is left at the last accepted step. Throws std::invalid_argument
// for a plan that does not fit the problem (a prescribed joint whose alpha
// is free, every alpha fixed under the average actuation).
DeploymentResult deploy(LinkageProblem& problem, const DeploymentPlan& plan,
                        const DeploymentOptions& options = {},
                        const DeploymentCallbacks& callbacks = {});

}  // namespace xshell
