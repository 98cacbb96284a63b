// Masses and damping for statics by damped dynamics.
//
// The dynamics M q'' + C q' + grad E(q) = 0 use C = c M (mass-proportional
// damping). Along an eigenmode x of the pencil (H, M), H x = lambda M x,
// the motion obeys a'' + c a' + lambda a = 0: every mode decays at least as
// fast as exp(-c t / 2) when c <= 2 sqrt(lambda), and the slowest mode is
// critically damped for c = 2 sqrt(lambda_min). That is the automatic
// choice: all modes then decay at the best rate mass-proportional damping
// allows for the slowest one.
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "integrators/linear_algebra/cholesky_solver.hpp"
#include "integrators/linear_algebra/shifted_factorization.hpp"

namespace xshell {

// Fictitious masses of dynamic relaxation (Barnes 1999; Gerschgorin):
// m_i = sum_j |H_ij|, which bounds the eigenvalues of M^-1 H to [-1, 1].
// Entries below floor_ratio * max_i m_i are raised to it (all ones if H = 0).
Eigen::VectorXd fictitious_mass(const Eigen::SparseMatrix<double>& H, double floor_ratio = 1e-8);

struct LowestMode {
  double eigenvalue = 0.0;  // Rayleigh quotient x'Hx / x'Mx of the last iterate
  bool shifted = false;     // H was not positive definite (inverse iteration on H + s M)
  double shift = 0.0;       // s (0 when H is positive definite)
  int iterations = 0;
  int factorizations = 0;  // numeric factorizations made
  bool ok = false;         // false if no factorization could be made
  Eigen::VectorXd vector;  // the last iterate, x'Mx = 1
};

// Estimates the lowest eigenvalue of H x = lambda M x by `iterations` steps
// of inverse iteration x <- (H + s M)^-1 M x, with s = 0 when H is positive
// definite and the shift of factorize_with_shift otherwise (the iteration
// then finds the lowest, possibly negative, eigenvalue: the one closest to
// -s). Converges like (mu_1 / mu_2)^k: a rough estimate suffices here.
LowestMode estimate_lowest_mode(CholeskySolver& solver, const Eigen::SparseMatrix<double>& H,
                                const Eigen::VectorXd& mass, int iterations = 20,
                                const ShiftOptions& shift = {});

// The lowest mode and, when it is unstable (negative), also the lowest
// stable (positive) one: inverse iteration with the same factorization,
// M-orthogonal to the unstable modes found before (at most max_unstable of
// them). `warm`: a previous estimate whose vectors start the iterations.
struct ModeEstimate {
  LowestMode lowest;
  LowestMode stable;             // == lowest when that is stable; ok = false if not found
  int unstable_modes = 0;        // negative eigenvalues found
  double certified_shift = 0.0;  // s with H + s M positive definite (0 if H is)
};
// Modes with eigenvalues at or below zero_floor (zero modes, such as the
// rigid swing of a free arm) count as not stable: `stable` is the lowest
// mode above it. Each mode's iteration ends before `iterations` once the
// Rayleigh quotient of (H + s M)^-1 M changes by less than converged_change
// (relative) from one iteration to the next: a mode well separated from
// the next one needs only a few solves.
ModeEstimate estimate_modes(CholeskySolver& solver, const Eigen::SparseMatrix<double>& H,
                            const Eigen::VectorXd& mass, int iterations = 20,
                            const ShiftOptions& shift = {}, int max_unstable = 4,
                            const ModeEstimate* warm = nullptr, double zero_floor = 0.0,
                            double converged_change = 1e-6);

// c = 2 sqrt(|lambda_min|) (critical damping of the slowest mode; near a
// saddle, |lambda_min| is the growth rate scale of the unstable mode),
// with |lambda_min| raised to 1e-12 * trace(H)/trace(M) when smaller (a
// zero mode) and c = 1 if nothing else is available.
double automatic_damping(const LowestMode& mode, const Eigen::SparseMatrix<double>& H,
                         const Eigen::VectorXd& mass);

}  // namespace xshell
