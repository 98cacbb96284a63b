#include "integrators/linear_algebra/cholesky_pattern.hpp"

#include <algorithm>
#include <deque>
#include <mutex>
#include <stdexcept>

#include "integrators/linear_algebra/cholmod_handles.hpp"
#include "integrators/linear_algebra/cholmod_threads.hpp"

namespace xshell {

namespace {

// Upper triangle of A's pattern plus the full diagonal.
Eigen::SparseMatrix<double> upper_pattern(const Eigen::SparseMatrix<double>& A) {
  const int n = static_cast<int>(A.cols());
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(static_cast<size_t>(A.nonZeros()) / 2 + static_cast<size_t>(n));
  for (int j = 0; j < n; ++j) {
    entries.emplace_back(j, j, 0.0);
    for (Eigen::SparseMatrix<double>::InnerIterator it(A, j); it; ++it)
      if (it.row() < j) entries.emplace_back(static_cast<int>(it.row()), j, 0.0);
  }
  Eigen::SparseMatrix<double> upper(n, n);
  upper.setFromTriplets(entries.begin(), entries.end());
  upper.makeCompressed();
  return upper;
}

// cholmod_analyze of the symmetric matrix stored as `storage` in `m`.
cholmod_factor* symbolic_analysis(Eigen::SparseMatrix<double>& m, SymmetricStorage storage,
                                  cholmod_common* c) {
  cholmod_sparse view = sparse_view(m, storage);
  cholmod_factor* L = nullptr;
  {
    const CholmodThreads threads;
    L = cholmod_analyze(&view, c);
  }
  if (L == nullptr) throw std::runtime_error("cholmod_analyze failed");
  return L;
}

// CHOLMOD's fill-reducing permutation (with its postordering) for the
// symmetric matrix whose upper triangle is `upper`.
std::vector<int> fill_reducing_permutation(Eigen::SparseMatrix<double>& upper, cholmod_common* c) {
  cholmod_factor* L = symbolic_analysis(upper, SymmetricStorage::Upper, c);
  const int* perm = static_cast<const int*>(L->Perm);
  std::vector<int> permutation(perm, perm + L->n);
  cholmod_free_factor(&L, c);
  return permutation;
}

// tril(P A P^T) of the upper triangle `upper`, `inverse` the inverse of P.
Eigen::SparseMatrix<double> permuted_lower(const Eigen::SparseMatrix<double>& upper,
                                           const std::vector<int>& inverse) {
  const int n = static_cast<int>(upper.cols());
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(static_cast<size_t>(upper.nonZeros()));
  for (int j = 0; j < n; ++j)
    for (Eigen::SparseMatrix<double>::InnerIterator it(upper, j); it; ++it) {
      const int a = inverse[static_cast<size_t>(it.row())], b = inverse[static_cast<size_t>(j)];
      entries.emplace_back(std::max(a, b), std::min(a, b), 0.0);
    }
  Eigen::SparseMatrix<double> lower(n, n);
  lower.setFromTriplets(entries.begin(), entries.end());
  lower.makeCompressed();
  return lower;
}

// The symbolic factor of the already permuted matrix whose lower triangle
// is `lower`: natural ordering, no further postordering.
cholmod_factor* analyze_in_order(Eigen::SparseMatrix<double>& lower, cholmod_common* c) {
  c->nmethods = 1;
  c->method[0].ordering = CHOLMOD_NATURAL;
  c->postorder = 0;
  cholmod_factor* L = symbolic_analysis(lower, SymmetricStorage::Lower, c);
  const int* perm = static_cast<const int*>(L->Perm);
  for (size_t k = 0; k < L->n; ++k)
    if (perm[k] != static_cast<int>(k)) {
      cholmod_free_factor(&L, c);
      throw std::logic_error("cholmod_analyze permuted a matrix given in natural order");
    }
  return L;
}

}  // namespace

bool has_pattern(const CholeskyPattern& pattern, const Eigen::SparseMatrix<double>& A) {
  const std::vector<int>& outer = pattern.source_outer;
  const std::vector<int>& inner = pattern.source_inner;
  if (static_cast<size_t>(A.cols()) + 1 != outer.size()) return false;
  if (static_cast<size_t>(A.nonZeros()) != inner.size()) return false;
  return std::equal(outer.begin(), outer.end(), A.outerIndexPtr()) &&
         std::equal(inner.begin(), inner.end(), A.innerIndexPtr());
}

std::shared_ptr<const CholeskyPattern> analyze_pattern(const Eigen::SparseMatrix<double>& A,
                                                       cholmod_common* common) {
  const int n = static_cast<int>(A.cols());
  auto p = std::make_shared<CholeskyPattern>();
  Eigen::SparseMatrix<double> upper = upper_pattern(A);
  p->permutation = fill_reducing_permutation(upper, common);
  // Entry (r, c) of A's upper triangle is entry (inverse[r], inverse[c]) of
  // P A P^T; its lower triangle keeps the larger index as the row.
  std::vector<int> inverse(static_cast<size_t>(n));
  for (int k = 0; k < n; ++k)
    inverse[static_cast<size_t>(p->permutation[static_cast<size_t>(k)])] = k;
  const Eigen::SparseMatrix<double>& lower = p->lower = permuted_lower(upper, inverse);
  auto position = [&](int row, int col) {
    const int a = inverse[static_cast<size_t>(row)], b = inverse[static_cast<size_t>(col)];
    const int r = std::max(a, b), c = std::min(a, b);
    const int* begin = lower.innerIndexPtr() + lower.outerIndexPtr()[c];
    const int* end = lower.innerIndexPtr() + lower.outerIndexPtr()[c + 1];
    return static_cast<int>(std::lower_bound(begin, end, r) - lower.innerIndexPtr());
  };
  p->scatter.assign(static_cast<size_t>(A.nonZeros()), -1);
  p->diagonal.resize(static_cast<size_t>(n));
  for (int j = 0; j < n; ++j) {
    p->diagonal[static_cast<size_t>(j)] = position(j, j);
    for (int k = A.outerIndexPtr()[j]; k < A.outerIndexPtr()[j + 1]; ++k) {
      const int row = A.innerIndexPtr()[k];
      if (row <= j) p->scatter[static_cast<size_t>(k)] = position(row, j);
    }
  }
  p->source_outer.assign(A.outerIndexPtr(), A.outerIndexPtr() + n + 1);
  p->source_inner.assign(A.innerIndexPtr(), A.innerIndexPtr() + A.nonZeros());
  p->symbolic = CholmodFactor(analyze_in_order(p->lower, p->common->get()), *p->common);
  return p;
}

cholmod_factor* copy_symbolic_factor(const CholeskyPattern& pattern, cholmod_common* common) {
  cholmod_factor* L = cholmod_copy_factor(pattern.symbolic.get(), common);
  if (L == nullptr) throw std::runtime_error("cholmod_copy_factor failed");
  return L;
}

std::shared_ptr<const CholeskyPattern> shared_pattern(const Eigen::SparseMatrix<double>& A,
                                                      cholmod_common* common, bool* reused) {
  static std::mutex mutex;
  static std::deque<std::shared_ptr<const CholeskyPattern>> recent;  // newest first
  {
    const std::lock_guard<std::mutex> lock(mutex);
    const auto found = std::find_if(recent.begin(), recent.end(),
                                    [&](const auto& p) { return has_pattern(*p, A); });
    if (found != recent.end()) {
      std::shared_ptr<const CholeskyPattern> p = *found;
      recent.erase(found);
      recent.push_front(p);
      *reused = true;
      return p;
    }
  }
  // Analysed outside the lock: other solvers' lookups need not wait.
  std::shared_ptr<const CholeskyPattern> p = analyze_pattern(A, common);
  const std::lock_guard<std::mutex> lock(mutex);
  recent.push_front(p);
  if (recent.size() > static_cast<size_t>(kRecentPatterns)) recent.pop_back();
  *reused = false;
  return p;
}

}  // namespace xshell
