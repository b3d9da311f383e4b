// The constraint modes from one factor of the bridge with its interface
// ordered last (solver/interface_last_factor.hpp) against the dense
// formula by Eigen, Psi = -K_II^-1 K_IG, and the same factor's solves of
// K_BB. On a 3D grid (CHOLMOD's supernodal factor) and a chain (its
// simplicial one).
#include <gtest/gtest.h>

#include <cholmod.h>

#include <Eigen/Cholesky>

#include "solver/interface_last_factor.hpp"
#include "solver/shift_invert_factor.hpp"

namespace railvsi {
namespace {

// A stiffness-like SPD matrix: the graph Laplacian of an nx x ny x nz grid
// (unit springs, uneven by position) plus a grounding spring on the first
// layer; DOF (x, y, z) is x + nx (y + ny z), so the last layer z = nz - 1
// comes last.
SparseMatrix grid(int nx, int ny, int nz) {
  const int n = nx * ny * nz;
  std::vector<Triplet> t;
  const auto id = [&](int x, int y, int z) { return x + nx * (y + ny * z); };
  const auto spring = [&](int a, int b, double k) {
    t.emplace_back(a, a, k);
    t.emplace_back(b, b, k);
    t.emplace_back(a, b, -k);
    t.emplace_back(b, a, -k);
  };
  for (int z = 0; z < nz; ++z)
    for (int y = 0; y < ny; ++y)
      for (int x = 0; x < nx; ++x) {
        const int a = id(x, y, z);
        const double k = 1.0 + 0.1 * ((x * 7 + y * 3 + z) % 5);
        if (x + 1 < nx) spring(a, id(x + 1, y, z), k);
        if (y + 1 < ny) spring(a, id(x, y + 1, z), 2.0 * k);
        if (z + 1 < nz) spring(a, id(x, y, z + 1), 0.5 * k);
        if (z == 0) t.emplace_back(a, a, 0.3);
      }
  SparseMatrix K(n, n);
  K.setFromTriplets(t.begin(), t.end());
  return K;
}

struct Dense {
  DenseMatrix Psi;
};

Dense dense_reference(const SparseMatrix& K_BB, int n_interior) {
  const DenseMatrix K(K_BB);
  const int g = static_cast<int>(K.rows()) - n_interior;
  Eigen::LLT<DenseMatrix> llt(K.topLeftCorner(n_interior, n_interior));
  Dense d;
  d.Psi = -llt.solve(K.topRightCorner(n_interior, g));
  return d;
}

double relative(const DenseMatrix& x, const DenseMatrix& ref) {
  if (x.rows() != ref.rows() || x.cols() != ref.cols() || !x.allFinite() || ref.size() == 0) return 1.0;
  return (x - ref).cwiseAbs().maxCoeff() / ref.cwiseAbs().maxCoeff();
}

struct Measured {
  double psi = 1.0, solve = 1.0;  // solve: |K_BB X - B| / |B| through the factor
  bool supernodal = false;
};

Measured measure(const SparseMatrix& K_BB, int n_interior, int column_block) {
  const int n_interface = static_cast<int>(K_BB.rows()) - n_interior;
  const SparseMatrix I_BB = [&] {
    SparseMatrix I(K_BB.rows(), K_BB.cols());
    I.setIdentity();
    return I;
  }();
  Status ordered;
  std::vector<int> order = interface_last_ordering(K_BB.topLeftCorner(n_interior, n_interior), n_interface, ordered);
  EXPECT_TRUE(ordered.ok()) << ordered.message();
  ShiftInvertFactor factor(K_BB, I_BB);
  factor.order_as(std::move(order));
  EXPECT_TRUE(factor.factorize(0.0).ok()) << factor.status().message();
  Measured m;
  if (!factor.cholmod_l()) return m;
  m.supernodal = factor.cholmod_l()->is_super != 0;
  const Dense ref = dense_reference(K_BB, n_interior);
  DenseMatrix Psi;
  EXPECT_TRUE(constraint_modes(factor, n_interior, column_block, Psi));
  m.psi = relative(Psi, ref.Psi);
  // The same factor still solves K_BB itself (the modes' first shift).
  const DenseMatrix B = DenseMatrix::Identity(K_BB.rows(), 3);
  DenseMatrix X;
  EXPECT_TRUE(factor.solve(B, X));
  m.solve = relative(DenseMatrix(K_BB) * X, B);
  return m;
}

// Each case: the grid, its interior's size, the column block, the factor
// kind CHOLMOD picks, and the tolerances (3x the errors measured
// 2026-11-28, relative to the largest entry): Psi, solve.
struct Case {
  const char* name;
  int nx, ny, nz, n_interior, column_block;
  bool supernodal;
  double psi, solve;
};

class InterfaceLastFactorCases : public ::testing::TestWithParam<Case> {};

TEST_P(InterfaceLastFactorCases, ConstraintModesEqualTheDenseFormulaAndTheFactorStillSolvesTheBridge) {
  const Case& c = GetParam();
  const Measured m = measure(grid(c.nx, c.ny, c.nz), c.n_interior, c.column_block);
  EXPECT_EQ(m.supernodal, c.supernodal);
  std::printf("[interface last, %s] Psi %.2e, solve %.2e\n", c.name, m.psi, m.solve);
  EXPECT_LT(m.psi, c.psi);
  EXPECT_LT(m.solve, c.solve);
}

INSTANTIATE_TEST_SUITE_P(
    Factors, InterfaceLastFactorCases,
    ::testing::Values(
        // 12 x 10 x 8 grid, 960 DOFs, the top layer (120) the interface:
        // supernodal; measured Psi 7.7e-16, solve 2.7e-16.
        Case{"supernodal", 12, 10, 8, 12 * 10 * 7, 32, true, 2.3e-15, 8.1e-16},
        // A chain of 200 springs, the last 5 DOFs the interface, blocks of
        // 2 columns: simplicial; measured 3.5e-16, 3.3e-16.
        Case{"simplicial", 200, 1, 1, 195, 2, false, 1.1e-15, 1.0e-15}));

TEST(InterfaceLastFactor, RefusesAFactorInAnotherOrder) {
  const SparseMatrix K = grid(6, 5, 4);
  SparseMatrix I(K.rows(), K.cols());
  I.setIdentity();
  ShiftInvertFactor factor(K, I);  // CHOLMOD's own ordering
  ASSERT_TRUE(factor.factorize(0.0).ok());
  DenseMatrix Psi;
  EXPECT_FALSE(constraint_modes(factor, 6 * 5 * 3, 8, Psi));
}

}  // namespace
}  // namespace railvsi
