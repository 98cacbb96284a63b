#include "cholesky_solver.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "cholmod_handles.hpp"
#include "cholmod_threads.hpp"

namespace xshell {

namespace {

bool same_pattern(const Eigen::SparseMatrix<double>& A, const std::vector<int>& outer,
                  const std::vector<int>& inner) {
  if (static_cast<size_t>(A.cols()) + 1 != outer.size()) return false;
  if (static_cast<size_t>(A.nonZeros()) != inner.size()) return false;
  return std::equal(outer.begin(), outer.end(), A.outerIndexPtr()) &&
         std::equal(inner.begin(), inner.end(), A.innerIndexPtr());
}

}  // namespace

struct CholeskySolver::Impl {
  std::unique_ptr<CholmodCommon> common = std::make_unique<CholmodCommon>();
  CholmodFactor factor;
  CholmodDense x{*common}, y{*common}, e{*common};  // cholmod_solve2 workspaces

  // Pattern of the last analyzed input, to detect a change.
  std::vector<int> source_outer, source_inner;
  // Upper triangle plus the full diagonal, in CHOLMOD's (stype = 1) layout.
  Eigen::SparseMatrix<double> upper;
  std::vector<int> scatter;   // input value k -> index in upper, or -1 (lower triangle)
  std::vector<int> diagonal;  // column j -> index of (j, j) in upper
  bool ready = false;
  CholeskyStats stats;

  void analyze(const Eigen::SparseMatrix<double>& A);
  void fill(const Eigen::SparseMatrix<double>& A, const Eigen::VectorXd* shift);
};

void CholeskySolver::Impl::analyze(const Eigen::SparseMatrix<double>& A) {
  const int n = static_cast<int>(A.cols());
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(static_cast<size_t>(A.nonZeros()) / 2 + static_cast<size_t>(n));
  for (int j = 0; j < n; ++j) {
    entries.emplace_back(j, j, 0.0);
    for (Eigen::SparseMatrix<double>::InnerIterator it(A, j); it; ++it)
      if (it.row() < j) entries.emplace_back(static_cast<int>(it.row()), j, 0.0);
  }
  upper.resize(n, n);
  upper.setFromTriplets(entries.begin(), entries.end());  // sums duplicates
  upper.makeCompressed();

  auto position = [&](int row, int col) {
    const int* begin = upper.innerIndexPtr() + upper.outerIndexPtr()[col];
    const int* end = upper.innerIndexPtr() + upper.outerIndexPtr()[col + 1];
    return static_cast<int>(std::lower_bound(begin, end, row) - upper.innerIndexPtr());
  };
  scatter.assign(static_cast<size_t>(A.nonZeros()), -1);
  diagonal.resize(static_cast<size_t>(n));
  for (int j = 0; j < n; ++j) {
    diagonal[static_cast<size_t>(j)] = position(j, j);
    for (int k = A.outerIndexPtr()[j]; k < A.outerIndexPtr()[j + 1]; ++k) {
      const int row = A.innerIndexPtr()[k];
      if (row <= j) scatter[static_cast<size_t>(k)] = position(row, j);
    }
  }
  source_outer.assign(A.outerIndexPtr(), A.outerIndexPtr() + n + 1);
  source_inner.assign(A.innerIndexPtr(), A.innerIndexPtr() + A.nonZeros());

  cholmod_sparse view = sparse_view(upper, SymmetricStorage::Upper);
  factor.reset();
  cholmod_factor* L = nullptr;
  {
    const CholmodThreads threads;
    L = cholmod_analyze(&view, common->get());
  }
  if (L == nullptr) throw std::runtime_error("cholmod_analyze failed");
  factor = CholmodFactor(L, *common);
  ready = false;
  ++stats.analyses;
}

void CholeskySolver::Impl::fill(const Eigen::SparseMatrix<double>& A,
                                const Eigen::VectorXd* shift) {
  double* values = upper.valuePtr();
  std::fill(values, values + upper.nonZeros(), 0.0);
  const double* source = A.valuePtr();
  for (size_t k = 0; k < scatter.size(); ++k)
    if (scatter[k] >= 0) values[scatter[k]] += source[k];
  if (shift != nullptr)
    for (size_t j = 0; j < diagonal.size(); ++j)
      values[diagonal[j]] += (*shift)[static_cast<Eigen::Index>(j)];
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
  if (!s.factor || !same_pattern(A, s.source_outer, s.source_inner)) s.analyze(A);
  s.ready = false;
  s.fill(A, diagonal_shift);
  const double* values = s.upper.valuePtr();
  if (!std::all_of(values, values + s.upper.nonZeros(), [](double v) { return std::isfinite(v); }))
    return FactorizationStatus::NonFinite;

  cholmod_sparse view = sparse_view(s.upper, SymmetricStorage::Upper);
  cholmod_common* c = s.common->get();
  ++s.stats.factorizations;
  int ok = 0;
  {
    const CholmodThreads threads;
    ok = cholmod_factorize(&view, s.factor.get(), c);
  }
  if (c->status == CHOLMOD_NOT_POSDEF || s.factor.get()->minor < s.factor.get()->n) {
    ++s.stats.failed_factorizations;
    return FactorizationStatus::NotPositiveDefinite;
  }
  if (!ok || c->status < CHOLMOD_OK) throw std::runtime_error("cholmod_factorize failed");
  s.ready = true;
  return FactorizationStatus::PositiveDefinite;
}

bool CholeskySolver::factorized() const { return impl_->ready; }

void CholeskySolver::solve(const double* b, double* x) {
  Impl& s = *impl_;
  if (!s.ready) throw std::logic_error("CholeskySolver::solve without a successful factorization");
  const Eigen::Index n = s.upper.cols();
  Eigen::VectorXd rhs = Eigen::Map<const Eigen::VectorXd>(b, n);
  cholmod_dense B = dense_view(rhs);
  const CholmodThreads threads;
  if (!cholmod_solve2(CHOLMOD_A, s.factor.get(), &B, nullptr, s.x.handle(), nullptr, s.y.handle(),
                      s.e.handle(), s.common->get()))
    throw std::runtime_error("cholmod_solve2 failed");
  const double* solution = static_cast<const double*>(s.x.get()->x);
  std::copy(solution, solution + n, x);
  ++s.stats.solves;
}

Eigen::VectorXd CholeskySolver::solve(const Eigen::VectorXd& b) {
  Eigen::VectorXd x(b.size());
  solve(b.data(), x.data());
  return x;
}

Eigen::Index CholeskySolver::size() const { return impl_->upper.cols(); }

const CholeskyStats& CholeskySolver::stats() const { return impl_->stats; }

}  // namespace xshell
