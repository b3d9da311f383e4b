#pragma once
// RAII owners of CHOLMOD objects. A cholmod_common is not thread-safe, so
// every owner of a factor keeps its own, and every solve workspace brings
// another one.
#include <cholmod.h>

#include <memory>

#include "core/types.hpp"

namespace railvsi {

class CholmodCommon {
 public:
  CholmodCommon();
  ~CholmodCommon();
  CholmodCommon(const CholmodCommon&) = delete;
  CholmodCommon& operator=(const CholmodCommon&) = delete;
  cholmod_common* get() { return &c_; }

 private:
  cholmod_common c_;
};

struct CholmodFactorDeleter {
  cholmod_common* common;
  void operator()(cholmod_factor* L) const { cholmod_free_factor(&L, common); }
};
struct CholmodDenseDeleter {
  cholmod_common* common;
  void operator()(cholmod_dense* X) const { cholmod_free_dense(&X, common); }
};
using CholmodDensePtr = std::unique_ptr<cholmod_dense, CholmodDenseDeleter>;

// Non-owning CHOLMOD views of Eigen storage (no copies). The sparse view
// reads the upper triangle of a symmetric matrix.
cholmod_sparse cholmod_view_symmetric(const SparseMatrix& A);
cholmod_dense cholmod_view(Eigen::Ref<DenseMatrix> B);

}  // namespace railvsi
