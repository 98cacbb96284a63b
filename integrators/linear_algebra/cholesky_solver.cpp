#include "integrators/linear_algebra/cholesky_solver.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <optional>
#include <stdexcept>
#include <vector>

#include "integrators/linear_algebra/cholesky_pattern.hpp"
#include "integrators/linear_algebra/cholmod_handles.hpp"
#include "integrators/linear_algebra/cholmod_threads.hpp"

namespace xshell {

// CHOLMOD factorizes P A P^T for its fill-reducing permutation P. Handed the
// upper triangle of A, cholmod_factorize first builds tril(P A P^T) in new
// storage (a transpose and an allocation, about a sixth of a factorization
// here). So the solver keeps tril(P A P^T) itself, filled straight from the
// input through a precomputed scatter map, and hands it to a factor analyzed
// with the natural ordering (the permutation is then ours): CHOLMOD uses it
// in place. Solves apply P to the right-hand side and P^T to the solution.
struct CholeskySolver::Impl {
  std::unique_ptr<CholmodCommon> common = std::make_unique<CholmodCommon>();
  CholmodFactor factor;
  CholmodDense x{*common}, y{*common}, e{*common};  // cholmod_solve2 workspaces

  std::shared_ptr<const CholeskyPattern> pattern;  // of the last analyzed input
  Eigen::VectorXd values;                          // of tril(P A P^T), in pattern->lower's layout
  // The values of the last factorization, and its status when it ran to
  // the end (none after an analysis): the next values are
  // filled into `values`, and the two swap after a factorization.
  Eigen::VectorXd factorized_values;
  std::optional<FactorizationStatus> factorized_status;
  Eigen::VectorXd permuted;  // solve workspace
  bool ready = false;
  CholeskyStats stats;

  Eigen::Index size() const { return pattern ? pattern->lower.cols() : 0; }
  bool analyzed_for(const Eigen::SparseMatrix<double>& A) const;
  void analyze(const Eigen::SparseMatrix<double>& A);
  void fill(const Eigen::SparseMatrix<double>& A, const Eigen::VectorXd* shift);
  // Keeps the values just factorized and their status; returns it.
  FactorizationStatus remember(FactorizationStatus status) {
    values.swap(factorized_values);
    factorized_status = status;
    return status;
  }
  // `system` (CHOLMOD_A, _L, _Lt) solved for the right-hand side `permuted`,
  // the solution copied to `out` (may be permuted.data()).
  void solve_permuted(int system, double* out);
  void require_factorization() const;
  // The halves take the factor for G of G G^T: an LL^T one
  // (cholmod_handles.cpp asks for supernodal LL^T only), not the unit L of
  // an LDL^T.
  void require_ll_factor() const;
};

bool CholeskySolver::Impl::analyzed_for(const Eigen::SparseMatrix<double>& A) const {
  return factor && pattern && has_pattern(*pattern, A);
}

void CholeskySolver::Impl::analyze(const Eigen::SparseMatrix<double>& A) {
  factor.reset();
  pattern.reset();
  ready = false;
  bool reused = false;
  std::shared_ptr<const CholeskyPattern> p = shared_pattern(A, common->get(), &reused);
  values.setZero(p->lower.nonZeros());
  factorized_values.resize(0);
  factorized_status.reset();
  permuted.resize(A.cols());
  factor = CholmodFactor(copy_symbolic_factor(*p, common->get()), *common);
  pattern = std::move(p);
  ++stats.analyses;
  if (reused) ++stats.reused_patterns;
}

void CholeskySolver::Impl::fill(const Eigen::SparseMatrix<double>& A,
                                const Eigen::VectorXd* shift) {
  values.setZero(pattern->lower.nonZeros());
  const double* source = A.valuePtr();
  const std::vector<int>& scatter = pattern->scatter;
  for (size_t k = 0; k < scatter.size(); ++k)
    if (scatter[k] >= 0) values[scatter[k]] += source[k];
  if (shift != nullptr) {
    const std::vector<int>& diagonal = pattern->diagonal;
    for (size_t j = 0; j < diagonal.size(); ++j)
      values[diagonal[j]] += (*shift)[static_cast<Eigen::Index>(j)];
  }
}

CholeskySolver::CholeskySolver() : impl_(std::make_unique<Impl>()) {}
CholeskySolver::~CholeskySolver() = default;
CholeskySolver::CholeskySolver(CholeskySolver&&) noexcept = default;
CholeskySolver& CholeskySolver::operator=(CholeskySolver&&) noexcept = default;

FactorizationStatus CholeskySolver::factorize(const Eigen::SparseMatrix<double>& A,
                                              const Eigen::VectorXd* diagonal_shift) {
  if (A.rows() != A.cols()) throw std::invalid_argument("CholeskySolver: matrix is not square");
  if (!A.isCompressed()) throw std::invalid_argument("CholeskySolver: matrix is not compressed");
  if (diagonal_shift != nullptr && diagonal_shift->size() != A.cols())
    throw std::invalid_argument("CholeskySolver: shift has the wrong size");
  Impl& s = *impl_;
  if (!s.analyzed_for(A)) s.analyze(A);
  s.ready = false;
  s.fill(A, diagonal_shift);
  if (!s.values.allFinite()) return FactorizationStatus::NonFinite;
  if (s.factorized_status && s.values == s.factorized_values) {
    s.ready = *s.factorized_status == FactorizationStatus::PositiveDefinite;
    return *s.factorized_status;
  }
  s.factorized_status.reset();

  cholmod_sparse view = sparse_view(s.pattern->lower, s.values.data(), SymmetricStorage::Lower);
  cholmod_common* c = s.common->get();
  ++s.stats.factorizations;
  int ok = 0;
  {
    const CholmodThreads threads;
    ok = cholmod_factorize(&view, s.factor.get(), c);
  }
  if (c->status == CHOLMOD_NOT_POSDEF || s.factor.get()->minor < s.factor.get()->n) {
    ++s.stats.failed_factorizations;
    return s.remember(FactorizationStatus::NotPositiveDefinite);
  }
  if (!ok || c->status < CHOLMOD_OK) throw std::runtime_error("cholmod_factorize failed");
  s.ready = true;
  return s.remember(FactorizationStatus::PositiveDefinite);
}

bool CholeskySolver::factorized() const { return impl_->ready; }

void CholeskySolver::Impl::require_factorization() const {
  if (!ready) throw std::logic_error("CholeskySolver::solve without a successful factorization");
}

void CholeskySolver::Impl::require_ll_factor() const {
  require_factorization();
  if (!factor.get()->is_ll) throw std::logic_error("CholeskySolver: the factor is not LL^T");
}

void CholeskySolver::Impl::solve_permuted(int system, double* out) {
  cholmod_dense B = dense_view(permuted);
  {
    const CholmodThreads threads;
    if (!cholmod_solve2(system, factor.get(), &B, nullptr, x.handle(), nullptr, y.handle(),
                        e.handle(), common->get()))
      throw std::runtime_error("cholmod_solve2 failed");
  }
  const double* solution = static_cast<const double*>(x.get()->x);
  std::copy(solution, solution + permuted.size(), out);
}

void CholeskySolver::solve(const double* b, double* x) {
  Impl& s = *impl_;
  s.require_factorization();
  const Eigen::Index n = s.size();
  const std::vector<int>& permutation = s.pattern->permutation;
  for (Eigen::Index k = 0; k < n; ++k) s.permuted[k] = b[permutation[static_cast<size_t>(k)]];
  s.solve_permuted(CHOLMOD_A, s.permuted.data());
  for (Eigen::Index k = 0; k < n; ++k) x[permutation[static_cast<size_t>(k)]] = s.permuted[k];
  ++s.stats.solves;
}

void CholeskySolver::solve_lower(const double* b, double* y) {
  Impl& s = *impl_;
  s.require_ll_factor();
  const Eigen::Index n = s.size();
  const std::vector<int>& permutation = s.pattern->permutation;
  for (Eigen::Index k = 0; k < n; ++k) s.permuted[k] = b[permutation[static_cast<size_t>(k)]];
  s.solve_permuted(CHOLMOD_L, y);
}

void CholeskySolver::solve_upper(const double* y, double* x) {
  Impl& s = *impl_;
  s.require_ll_factor();
  const Eigen::Index n = s.size();
  const std::vector<int>& permutation = s.pattern->permutation;
  std::copy(y, y + n, s.permuted.data());
  s.solve_permuted(CHOLMOD_Lt, s.permuted.data());
  for (Eigen::Index k = 0; k < n; ++k) x[permutation[static_cast<size_t>(k)]] = s.permuted[k];
}

Eigen::VectorXd CholeskySolver::solve(const Eigen::VectorXd& b) {
  Eigen::VectorXd x(b.size());
  solve(b.data(), x.data());
  return x;
}

Eigen::Index CholeskySolver::size() const { return impl_->size(); }

const CholeskyStats& CholeskySolver::stats() const { return impl_->stats; }

}  // namespace xshell
