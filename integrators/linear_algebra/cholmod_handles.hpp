// RAII owners for the CHOLMOD objects the solvers use, and non-owning
// CHOLMOD headers ("views") over Eigen storage.
//
// Every CHOLMOD object must be freed with the cholmod_common it was created
// with, so the owners below keep a pointer to it. The common itself is
// neither copyable nor movable; hold it by unique_ptr to move a solver.
// All objects use the int interface (itype CHOLMOD_INT), matching the
// default StorageIndex of Eigen::SparseMatrix.
#pragma once

#include <cholmod.h>

#include <Eigen/Core>
#include <Eigen/SparseCore>

namespace xshell {

// cholmod_start / cholmod_finish. Configured silent (print = 0: failures are
// reported through return values, never printed) and for LL^T
// factorizations that stop at the first non-positive pivot.
class CholmodCommon {
 public:
  CholmodCommon();
  ~CholmodCommon();
  CholmodCommon(const CholmodCommon&) = delete;
  CholmodCommon& operator=(const CholmodCommon&) = delete;

  cholmod_common* get() { return &common_; }

 private:
  cholmod_common common_;
};

// Owns a cholmod_factor (from cholmod_analyze).
class CholmodFactor {
 public:
  CholmodFactor() = default;
  CholmodFactor(cholmod_factor* factor, CholmodCommon& common)
      : factor_(factor), common_(common.get()) {}
  ~CholmodFactor() { reset(); }
  CholmodFactor(CholmodFactor&& other) noexcept { *this = std::move(other); }
  CholmodFactor& operator=(CholmodFactor&& other) noexcept;
  CholmodFactor(const CholmodFactor&) = delete;
  CholmodFactor& operator=(const CholmodFactor&) = delete;

  cholmod_factor* get() const { return factor_; }
  explicit operator bool() const { return factor_ != nullptr; }
  void reset();

 private:
  cholmod_factor* factor_ = nullptr;
  cholmod_common* common_ = nullptr;
};

// Owns a cholmod_dense. Also usable as an in/out handle for cholmod_solve2,
// which allocates or reuses the matrix behind `handle()`.
class CholmodDense {
 public:
  explicit CholmodDense(CholmodCommon& common) : common_(common.get()) {}
  ~CholmodDense() { reset(); }
  CholmodDense(CholmodDense&& other) noexcept { *this = std::move(other); }
  CholmodDense& operator=(CholmodDense&& other) noexcept;
  CholmodDense(const CholmodDense&) = delete;
  CholmodDense& operator=(const CholmodDense&) = delete;

  cholmod_dense* get() const { return dense_; }
  cholmod_dense** handle() { return &dense_; }
  void reset();

 private:
  cholmod_dense* dense_ = nullptr;
  cholmod_common* common_ = nullptr;
};

// Which triangle of a symmetric matrix CHOLMOD reads (cholmod_sparse::stype).
enum class SymmetricStorage { Upper = 1, Lower = -1, Unsymmetric = 0 };

// A cholmod_sparse header over the arrays of a compressed Eigen matrix
// (makeCompressed() first; inner indices sorted, as Eigen keeps them). The
// view is valid while the matrix lives and its storage is not reallocated.
// With SymmetricStorage::Upper CHOLMOD reads only the entries with
// row <= column, so a matrix storing both triangles can be passed as is.
cholmod_sparse sparse_view(Eigen::SparseMatrix<double>& matrix, SymmetricStorage storage);
// The same over the structure of `pattern` with the values in `values`
// (pattern.nonZeros() of them): for CHOLMOD calls that read the matrix
// only (analysis, factorization), several value arrays sharing one
// structure.
cholmod_sparse sparse_view(const Eigen::SparseMatrix<double>& pattern, double* values,
                           SymmetricStorage storage);

// A one-column cholmod_dense header over a vector (valid while it lives).
cholmod_dense dense_view(Eigen::Ref<Eigen::VectorXd> vector);

}  // namespace xshell
