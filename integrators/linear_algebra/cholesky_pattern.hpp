// The part of CholeskySolver's symbolic analysis that depends on the input's
// sparsity pattern alone: CHOLMOD's fill-reducing ordering, the structure of
// the permuted lower triangle and the map that scatters an input into it.
//
// Solvers of one pattern share it. A run that creates solvers again and
// again for the same matrices (damped dynamics at every deployment step:
// the damping estimate, IDA's Jacobian and the end game each own one) finds
// the pattern analysed before in a small process-wide list of the most
// recent ones, where a new analysis of hourglass's 1e6-entry Hessian took
// about 30 ms, as long as a factorization. The supernodal structure of the
// permuted matrix comes with it; each solver copies it into a factor of its
// own.
#pragma once

#include <cholmod.h>

#include <Eigen/SparseCore>
#include <memory>
#include <vector>

#include "integrators/linear_algebra/cholmod_handles.hpp"

namespace xshell {

struct CholeskyPattern {
  std::vector<int> source_outer, source_inner;  // the analysed input's pattern
  // tril(P A P^T) plus the full diagonal, in CHOLMOD's (stype = -1)
  // layout: its structure (the values live in each solver's own array).
  Eigen::SparseMatrix<double> lower;
  std::vector<int> permutation;  // P: row k of P A P^T is row permutation[k] of A
  std::vector<int> scatter;      // input value k -> index in lower, or -1 (lower triangle of A)
  std::vector<int> diagonal;     // unknown j -> index of its diagonal entry in lower
  // The symbolic factor of `lower` in its natural order (it is permuted
  // already), in a CHOLMOD context of its own.
  std::unique_ptr<CholmodCommon> common = std::make_unique<CholmodCommon>();
  CholmodFactor symbolic;
};

// True when A (compressed) has the pattern `pattern` was analysed for.
bool has_pattern(const CholeskyPattern& pattern, const Eigen::SparseMatrix<double>& A);

// A copy of pattern.symbolic in `common`, for a solver to factorize into.
cholmod_factor* copy_symbolic_factor(const CholeskyPattern& pattern, cholmod_common* common);

// A new analysis of A's pattern (the ordering with `common`'s settings).
std::shared_ptr<const CholeskyPattern> analyze_pattern(const Eigen::SparseMatrix<double>& A,
                                                       cholmod_common* common);

// The analysis of A's pattern: one of the kRecentPatterns analysed last in
// this process (`*reused` set), or a new one, which then replaces the
// oldest. Every CholmodCommon is configured alike, so an ordering found
// with one holds for all. Thread-safe.
constexpr int kRecentPatterns = 2;
std::shared_ptr<const CholeskyPattern> shared_pattern(const Eigen::SparseMatrix<double>& A,
                                                      cholmod_common* common, bool* reused);

}  // namespace xshell
