#include "solver/cholmod_handles.hpp"

namespace railvsi {

CholmodCommon::CholmodCommon() {
  cholmod_start(&c_);
  c_.print = 0;
  c_.error_handler = nullptr;
}
CholmodCommon::~CholmodCommon() { cholmod_finish(&c_); }

cholmod_sparse cholmod_view_symmetric(const SparseMatrix& A) {
  cholmod_sparse s{};
  s.nrow = static_cast<size_t>(A.rows());
  s.ncol = static_cast<size_t>(A.cols());
  s.nzmax = static_cast<size_t>(A.nonZeros());
  s.p = const_cast<int*>(A.outerIndexPtr());
  s.i = const_cast<int*>(A.innerIndexPtr());
  s.x = const_cast<double*>(A.valuePtr());
  s.stype = 1;  // symmetric, upper triangle used
  s.itype = CHOLMOD_INT;
  s.xtype = CHOLMOD_REAL;
  s.dtype = CHOLMOD_DOUBLE;
  s.sorted = 1;
  s.packed = 1;
  return s;
}

cholmod_dense cholmod_view(Eigen::Ref<DenseMatrix> B) {
  cholmod_dense d{};
  d.nrow = static_cast<size_t>(B.rows());
  d.ncol = static_cast<size_t>(B.cols());
  d.nzmax = d.nrow * d.ncol;
  d.d = static_cast<size_t>(B.outerStride());
  d.x = B.data();
  d.xtype = CHOLMOD_REAL;
  d.dtype = CHOLMOD_DOUBLE;
  return d;
}

}  // namespace railvsi
