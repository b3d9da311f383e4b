#pragma once
// Linear-algebra vocabulary of the engine. SI units everywhere inside.
#include <Eigen/Dense>
#include <Eigen/Sparse>

namespace railvsi {

using Vector = Eigen::VectorXd;
using DenseMatrix = Eigen::MatrixXd;
using SparseMatrix = Eigen::SparseMatrix<double, Eigen::ColMajor, int>;
using Triplet = Eigen::Triplet<double, int>;

inline constexpr double kGravity_mps2 = 9.81;

}  // namespace railvsi
