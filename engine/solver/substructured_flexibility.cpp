#include "solver/substructured_flexibility.hpp"

#include <Eigen/SparseCholesky>
#include <algorithm>
#include <limits>

#include "core/input_error.hpp"

namespace railvsi {
namespace {

// Substructures tried: track DOFs more than `depth` couplings away from the
// nearest deck DOF, depth 1..kMaxDepth. Depth 1 keeps the most DOFs in T
// (all rail rotations on a direct-fastened deck); a deeper T has fewer
// coupling DOFs G (the static flexibility under a train on the approach).
constexpr int kMaxDepth = 3;

struct Partition {
  std::vector<int> T;           // substructure DOFs, increasing
  std::vector<int> G;           // DOFs outside T coupled to T, increasing
  std::vector<int> direct;      // (W \ T) u G, increasing: columns solved directly
};

// Distance in K's graph from each track DOF to the nearest non-track DOF,
// capped at kMaxDepth + 1; 0 for non-track DOFs. K is stored in full
// (both triangles), so column t lists the neighbours of t.
std::vector<int> track_distance(const SparseMatrix& K, const StructureModel& model, std::vector<int>& track) {
  const int n = static_cast<int>(K.rows());
  const StructureInfo& info = model.info();
  std::vector<int> dist(static_cast<std::size_t>(n), 0);
  for (int d = 0; d < n; ++d)
    if (info.is_track_dof(d)) dist[static_cast<std::size_t>(d)] = kMaxDepth + 1;
  for (const int d : model.rail_dofs()) dist[static_cast<std::size_t>(d)] = kMaxDepth + 1;
  track.clear();
  for (int d = 0; d < n; ++d)
    if (dist[static_cast<std::size_t>(d)] > 0) track.push_back(d);
  for (int level = 1; level <= kMaxDepth; ++level)
    for (const int t : track) {
      if (dist[static_cast<std::size_t>(t)] != kMaxDepth + 1) continue;
      for (SparseMatrix::InnerIterator it(K, t); it; ++it)
        if (dist[static_cast<std::size_t>(it.row())] == level - 1) {
          dist[static_cast<std::size_t>(t)] = level;
          break;
        }
    }
  return dist;
}

Partition partition_at(const SparseMatrix& K, const std::vector<int>& dist, const std::vector<int>& track,
                       const std::vector<int>& W, int depth) {
  Partition p;
  const auto in_T = [&](int d) { return dist[static_cast<std::size_t>(d)] > depth; };
  for (const int t : track)
    if (in_T(t)) p.T.push_back(t);
  for (const int t : p.T)
    for (SparseMatrix::InnerIterator it(K, t); it; ++it)
      if (!in_T(static_cast<int>(it.row()))) p.G.push_back(static_cast<int>(it.row()));
  for (const int w : W)
    if (!in_T(w)) p.direct.push_back(w);
  p.direct.insert(p.direct.end(), p.G.begin(), p.G.end());
  for (auto* v : {&p.G, &p.direct}) {
    std::sort(v->begin(), v->end());
    v->erase(std::unique(v->begin(), v->end()), v->end());
  }
  return p;
}

}  // namespace

DenseMatrix substructured_flexibility(const StructureOperator& op, const SparseMatrix& K,
                                      const StructureModel& model, const std::vector<int>& W,
                                      SolveWorkspace& ws, SubstructureSummary* summary, bool by_cost) {
  const auto m = static_cast<Eigen::Index>(W.size());
  const auto direct_only = [&] {
    if (summary) *summary = {static_cast<int>(m), 0};
    return op.flexibility_block(W, ws);
  };
  if (m == 0 || K.rows() != op.num_dofs()) return direct_only();

  std::vector<int> track;
  const std::vector<int> dist = track_distance(K, model, track);
  Partition best;
  bool found = false;
  for (int depth = 1; depth <= kMaxDepth; ++depth) {
    Partition p = partition_at(K, dist, track, W, depth);
    if (p.T.empty()) break;
    if (!found || p.direct.size() < best.direct.size()) {
      best = std::move(p);
      found = true;
    }
  }
  // Worth it only when it saves solves, and A^-1 on the W columns in T
  // stays within a few times the memory of the result.
  const double wt_columns = static_cast<double>(m) - static_cast<double>(best.direct.size());
  if (!found || best.direct.size() >= W.size() ||
      static_cast<double>(best.T.size()) * std::max(wt_columns, 1.0) > 4.0 * static_cast<double>(m * m) + 1e6)
    return direct_only();
  // Work in multiply-adds: a solve reads the factor twice; each column in T
  // costs a solve with A (~ a few times its nonzeros) and the dense
  // handling of its |T| rows.
  if (by_cost) {
    double a_nonzeros = 0.0;
    for (const int t : best.T) a_nonzeros += static_cast<double>(K.col(t).nonZeros());
    const double saved = (static_cast<double>(m) - static_cast<double>(best.direct.size())) * 2.0 * op.factor_nonzeros();
    const double extra = wt_columns * (8.0 * a_nonzeros + 4.0 * static_cast<double>(best.T.size()));
    if (!(saved > extra)) return direct_only();
  }

  const auto nT = static_cast<Eigen::Index>(best.T.size());
  const auto nD = static_cast<Eigen::Index>(best.direct.size());
  const auto nG = static_cast<Eigen::Index>(best.G.size());
  constexpr int kNone = -1;
  std::vector<int> pos_T(static_cast<std::size_t>(K.rows()), kNone), pos_D(pos_T), pos_G(pos_T);
  for (Eigen::Index i = 0; i < nT; ++i) pos_T[static_cast<std::size_t>(best.T[i])] = static_cast<int>(i);
  for (Eigen::Index i = 0; i < nD; ++i) pos_D[static_cast<std::size_t>(best.direct[i])] = static_cast<int>(i);
  for (Eigen::Index i = 0; i < nG; ++i) pos_G[static_cast<std::size_t>(best.G[i])] = static_cast<int>(i);

  // Solves with the whole structure: X = K^-1(W, direct).
  const DenseMatrix X = op.inverse_block(W, best.direct, ws);

  // A = K(T,T) and B = K(T,G).
  std::vector<Triplet> a, b;
  for (Eigen::Index j = 0; j < nT; ++j)
    for (SparseMatrix::InnerIterator it(K, best.T[j]); it; ++it) {
      const auto row = static_cast<std::size_t>(it.row());
      if (pos_T[row] != kNone) a.emplace_back(pos_T[row], static_cast<int>(j), it.value());
      else if (pos_G[row] != kNone) b.emplace_back(static_cast<int>(j), pos_G[row], it.value());
    }
  SparseMatrix A(nT, nT), B(nT, nG);
  A.setFromTriplets(a.begin(), a.end());
  B.setFromTriplets(b.begin(), b.end());

  // W's DOFs in T (positions in W), and the rows K^-1(j, G) for them.
  std::vector<Eigen::Index> wt;
  for (Eigen::Index i = 0; i < m; ++i)
    if (pos_T[static_cast<std::size_t>(W[static_cast<std::size_t>(i)])] != kNone) wt.push_back(i);
  const auto nWT = static_cast<Eigen::Index>(wt.size());
  DenseMatrix XG(nG, nWT);  // K^-1(G, j) = K^-1(j, G) for j in W and T
  for (Eigen::Index g = 0; g < nG; ++g) {
    const int col = pos_D[static_cast<std::size_t>(best.G[g])];
    for (Eigen::Index k = 0; k < nWT; ++k) XG(g, k) = X(wt[k], col);
  }
  DenseMatrix R = -(B * XG);
  for (Eigen::Index k = 0; k < nWT; ++k) R(pos_T[static_cast<std::size_t>(W[wt[k]])], k) += 1.0;
  const Eigen::SimplicialLDLT<SparseMatrix> ldlt(A);
  if (ldlt.info() != Eigen::Success)
    throw InputError("/structure", "flexibility: the track substructure matrix could not be factorized");
  const DenseMatrix Y = ldlt.solve(R);  // K^-1(T, j) for j in W and T

  DenseMatrix F(m, m);
  for (Eigen::Index j = 0; j < m; ++j) {
    const int dj = W[static_cast<std::size_t>(j)];
    const int cj = pos_D[static_cast<std::size_t>(dj)];
    if (pos_T[static_cast<std::size_t>(dj)] == kNone) {
      F.col(j) = X.col(cj);  // a direct column
      continue;
    }
    const auto k = static_cast<Eigen::Index>(std::lower_bound(wt.begin(), wt.end(), j) - wt.begin());
    for (Eigen::Index i = 0; i < m; ++i) {
      const int di = W[static_cast<std::size_t>(i)];
      const int ti = pos_T[static_cast<std::size_t>(di)];
      // i outside T is a direct column: K^-1(i, j) = K^-1(j, i) = X(j, i).
      F(i, j) = ti != kNone ? Y(ti, k) : X(j, pos_D[static_cast<std::size_t>(di)]);
    }
  }
  if (summary) *summary = {static_cast<int>(nD), static_cast<int>(nT)};
  return F;
}

}  // namespace railvsi
