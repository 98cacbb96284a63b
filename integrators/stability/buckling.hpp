// Linearized buckling load factor: by how much the current loads can grow
// before the structure loses stability, estimated from two stiffnesses.
//
// With K_0 the free Hessian at the equilibrium of the unloaded structure
// (same supports, no gravity, no forces) and K_L the free Hessian at the
// equilibrium under the loads, the stiffness under the loads scaled by
// lambda is taken linear in lambda (the classical linearized buckling
// analysis, the load-dependent part being mostly the geometric stiffness of
// the internal forces):
//   K(lambda) = K_0 + lambda (K_L - K_0).
// The load factor is the smallest lambda > 0 at which K(lambda) turns
// singular: with K_0 positive definite,
//   (K_0 - K_L) phi = nu K_0 phi,  lambda = 1 / nu_max  (nu_max > 0),
// solved by Lanczos on a standard symmetric form (G^-1 S G^-T with the
// CHOLMOD factor G G^T of the other matrix): at a stable loaded state (K_L
// positive definite), on K_L^-1 K_0, whose eigenvalues lambda / (lambda - 1)
// set the wanted one apart from the unaffected modes (at 1); otherwise on
// K_0^-1 (K_0 - K_L), where the wanted nu sits next to the unaffected modes
// (at 0) and Lanczos can need many restarts (manta_ray deployed under
// gravity: 1000 restarts and 18 s, not converged, against 0.09 s). phi is
// the buckling mode, K_0-normalized.
// No lambda > 0 means the loads only stiffen the structure (at a stable
// loaded state: no lambda > 1): no buckling load.
// A load factor just above 1 (within ~1e-3) is what the linear
// interpolation gives when the unloaded equilibrium lies far from the
// loaded state (large rotations between them: a cantilever bent far, a
// deployed linkage whose unloaded equilibrium folds back): K(lambda) then
// turns singular right past the current loads along directions that K_0
// and K_L merely see rotated, and the estimate says nothing.
// The estimate is exact for a structure whose pre-buckling deformation is
// negligible (the Euler column: lambda P = pi^2 E I / (4 L^2) for a
// clamped-free column, tested) and a first-order estimate otherwise; it is
// the more accurate the closer the current loads are to the critical ones.
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <string>

#include "integrators/stability/analysis_deadline.hpp"

namespace xshell {

enum class BucklingStatus {
  Found,             // load_factor and mode are set
  NoBuckling,        // the loads never make K(lambda) singular for lambda > 0
  UnloadedUnstable,  // K_0 is not positive definite (a mechanism or unstable without loads)
  NotConverged,      // the eigensolver did not converge
  TimeLimit,         // options.deadline passed first ("time_limit")
  // Checked and found wrong (stability_analysis.hpp): the structure is still
  // stable under the loads times (1 + margin) load_factor ("refuted").
  Refuted,
};

struct BucklingOptions {
  double tolerance = 1e-10;  // Spectra's relative tolerance
  int max_restarts = 1000;
  AnalysisDeadline deadline;  // past it: status TimeLimit
  // K0 is known positive definite (an unshifted factorization of it
  // succeeded, as Newton's stability test at the unloaded equilibrium):
  // not factorized again only to check it.
  bool unloaded_positive_definite = false;
};

struct BucklingResult {
  BucklingStatus status = BucklingStatus::NotConverged;
  double load_factor = 0.0;  // lambda (dimensionless)
  Eigen::VectorXd mode;      // free unknowns, phi^T K_0 phi = 1
};

// K0, KL: n x n symmetric (both triangles), the same free unknowns.
// solver: the CHOLMOD solver to factorize K0 with (its symbolic analysis is
// reused when K0 has the pattern it last saw), or nullptr for its own.
class CholeskySolver;
BucklingResult linearized_buckling(const Eigen::SparseMatrix<double>& K0,
                                   const Eigen::SparseMatrix<double>& KL,
                                   const BucklingOptions& options = {},
                                   CholeskySolver* solver = nullptr);

const char* buckling_status_name(BucklingStatus status);

}  // namespace xshell
