#include "integrators/linear_algebra/cholmod_handles.hpp"

#include <stdexcept>
#include <utility>

namespace xshell {

CholmodCommon::CholmodCommon() {
  if (!cholmod_start(&common_)) throw std::runtime_error("cholmod_start failed");
  common_.print = 0;
  // LL^T only: a supernodal LL^T factorization (LAPACK potrf per supernode)
  // fails at the first non-positive pivot, which is how indefiniteness is
  // detected. A simplicial LDL^T would accept negative pivots silently.
  common_.supernodal = CHOLMOD_SUPERNODAL;
  common_.final_ll = 1;
  common_.quick_return_if_not_posdef = 1;
}

CholmodCommon::~CholmodCommon() { cholmod_finish(&common_); }

CholmodFactor& CholmodFactor::operator=(CholmodFactor&& other) noexcept {
  if (this != &other) {
    reset();
    factor_ = std::exchange(other.factor_, nullptr);
    common_ = other.common_;
  }
  return *this;
}

void CholmodFactor::reset() {
  if (factor_ != nullptr) cholmod_free_factor(&factor_, common_);
  factor_ = nullptr;
}

CholmodDense& CholmodDense::operator=(CholmodDense&& other) noexcept {
  if (this != &other) {
    reset();
    dense_ = std::exchange(other.dense_, nullptr);
    common_ = other.common_;
  }
  return *this;
}

void CholmodDense::reset() {
  if (dense_ != nullptr) cholmod_free_dense(&dense_, common_);
  dense_ = nullptr;
}

cholmod_sparse sparse_view(Eigen::SparseMatrix<double>& matrix, SymmetricStorage storage) {
  if (!matrix.isCompressed()) throw std::invalid_argument("sparse_view: matrix is not compressed");
  cholmod_sparse view{};
  view.nrow = static_cast<size_t>(matrix.rows());
  view.ncol = static_cast<size_t>(matrix.cols());
  view.nzmax = static_cast<size_t>(matrix.nonZeros());
  view.p = matrix.outerIndexPtr();
  view.i = matrix.innerIndexPtr();
  view.nz = nullptr;
  view.x = matrix.valuePtr();
  view.z = nullptr;
  view.stype = static_cast<int>(storage);
  view.itype = CHOLMOD_INT;
  view.xtype = CHOLMOD_REAL;
  view.dtype = CHOLMOD_DOUBLE;
  view.sorted = 1;
  view.packed = 1;
  return view;
}

cholmod_sparse sparse_view(const Eigen::SparseMatrix<double>& pattern, double* values,
                           SymmetricStorage storage) {
  // CHOLMOD's header has no const; the calls this view is for read it.
  cholmod_sparse view = sparse_view(const_cast<Eigen::SparseMatrix<double>&>(pattern), storage);
  view.x = values;
  return view;
}

cholmod_dense dense_view(Eigen::Ref<Eigen::VectorXd> vector) {
  cholmod_dense view{};
  view.nrow = static_cast<size_t>(vector.size());
  view.ncol = 1;
  view.nzmax = static_cast<size_t>(vector.size());
  view.d = static_cast<size_t>(vector.size());
  view.x = vector.data();
  view.z = nullptr;
  view.xtype = CHOLMOD_REAL;
  view.dtype = CHOLMOD_DOUBLE;
  return view;
}

}  // namespace xshell
