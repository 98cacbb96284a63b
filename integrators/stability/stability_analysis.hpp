// Stability of an equilibrium beyond yes/no: the lowest eigenpairs of the
// free Hessian (mass-weighted, eigen_modes.hpp) and the linearized buckling
// load factor of the current loads (buckling.hpp), whose unloaded stiffness
// K_0 is the free Hessian at the equilibrium of the same linkage with the
// same supports and no loads, found by Newton from the loaded state. A
// state held at its average opening angle (`held`: a deployment's end) is
// held there too, and the buckling is that of the held linkage: K_0 and K_L
// reduced to the constraint's null space (B^T K B, average_constraint.hpp),
// the mode carried back by B. Without the hold, a deployed linkage's
// unloaded equilibrium would be the one it springs back to, far away.
//
// The linear estimate is then checked by one more solve: Newton from the
// loaded state under the loads times (1 + check_margin) lambda, without
// leaving saddles (held at the average opening angle when `held`). A
// stable equilibrium there, reached without an indefinite Hessian on the
// way (a snap past a fold), refutes it (status Refuted): the structure
// carries more than the estimate says, which happens when the loads move
// it far (a soft deployed linkage under its own weight: the unloaded
// equilibrium lies far away, and the interpolation between the two
// stiffnesses turns singular just past the current loads). An unstable
// equilibrium or none (a fold passed) confirms it.
#pragma once

#include <Eigen/Core>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "integrators/deployment/average_constraint.hpp"
#include "integrators/newton/newton.hpp"
#include "integrators/stability/buckling.hpp"
#include "integrators/stability/eigen_modes.hpp"
#include "linkage/statics_problem.hpp"

namespace xshell {

// Where the analysis is: the start of each stage ("eigen_modes",
// "unloaded_equilibrium", "buckling", "buckling_check") with iteration 0,
// and each Newton iteration of the unloaded equilibrium and of the check.
struct StabilityProgress {
  std::string stage;
  long iteration = 0;
  std::optional<double> energy, gradient;
};

struct StabilityOptions {
  EigenModesOptions modes;        // how many eigenpairs (default 6)
  bool buckling = true;           // also the buckling load factor (one more Newton solve)
  NewtonOptions unloaded_newton;  // for the unloaded equilibrium and the check (no escape)
  double check_margin = 0.1;      // the check's loads: (1 + this) lambda; 0: no check
  // The average-angle constraint that holds the state (a deployment's end),
  // or nullptr: the check keeps the average.
  const AverageConstraint* held = nullptr;
  // The whole analysis' budget: the stage running when it passes stops with
  // the status "time_limit", and the later ones are skipped (the same).
  AnalysisDeadline deadline;
  std::function<void(const StabilityProgress&)> on_progress;  // optional
  // A CHOLMOD solver that has analysed the loaded state's Hessian and may
  // hold its factorization (Newton's stability test there), or nullptr:
  // the analysis works in it, skipping that analysis and factorization.
  CholeskySolver* factorized = nullptr;
};

struct StabilityAnalysis {
  EigenModes modes;                 // of H phi = lambda M phi at the loaded state
  bool loaded = false;              // some load acts (else no buckling analysis)
  bool unloaded_converged = false;  // the unloaded equilibrium was found
  std::string unloaded_reason;
  BucklingResult buckling;  // status UnloadedUnstable also when not converged; TimeLimit
                            // also when the deadline passed before it or in a Newton solve
  // The check's load factor (1 + check_margin) lambda, and whether the
  // state stayed stable there (status Refuted, the estimate kept in
  // buckling.load_factor).
  std::optional<double> check_factor;
  bool stable_at_check = false;
};

// problem: at its (loaded) equilibrium; its Hessian is reassembled.
StabilityAnalysis analyse_stability(LinkageProblem& problem, const StabilityOptions& options = {});

// Node displacements of every segment, [segment][node], for a vector over
// the free unknowns (a mode): the translational part of J v.
std::vector<std::vector<Eigen::Vector3d>> node_displacements(const LinkageProblem& problem,
                                                             const Eigen::VectorXd& free_vector);
// The same for each column of `free_vectors`, [column][segment][node]
// (each segment's map formed once).
std::vector<std::vector<std::vector<Eigen::Vector3d>>> node_displacements(
    const LinkageProblem& problem, const Eigen::MatrixXd& free_vectors);

}  // namespace xshell
