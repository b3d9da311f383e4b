// Reference path: eq. (36) of the paper assembled literally as one sparse
// matrix over (structure DOFs, vehicle DOFs, contact forces) and solved by
// UMFPACK at every Newton iteration. Slow by design; it shares no algebra
// with the condensed path, only the discrete equations.
#include <Eigen/UmfPackSupport>
#include <cmath>
#include <fmt/format.h>

#include "simulation/static_equilibrium.hpp"
#include "simulation/step_solver.hpp"

namespace railvsi {
namespace {

class ReferenceStepSolver final : public StepSolver {
 public:
  ReferenceStepSolver(const StructureModel& structure, const EffectiveMatrixFactors& f,
                      const TrainLayout& layout, const HhtCoefficients& h,
                      const StepSolverOptions& options)
      : coords_(structure), layout_(layout), options_(options), ns_(structure.num_dofs()),
        nv_(layout.num_vehicle_dofs), nc_(static_cast<int>(layout.contacts.size())) {
    const SparseMatrix Ks = effective_matrix(structure, f);
    for (int k = 0; k < Ks.outerSize(); ++k)
      for (SparseMatrix::InnerIterator it(Ks, k); it; ++it)
        base_.emplace_back(it.row(), it.col(), it.value());
    for (const VehicleInstance& v : layout.vehicles) {
      const DenseMatrix Kv = vehicle_effective_matrix(*v.model, h);
      for (Eigen::Index i = 0; i < Kv.rows(); ++i)
        for (Eigen::Index j = 0; j < Kv.cols(); ++j)
          if (Kv(i, j) != 0.0) base_.emplace_back(ns_ + v.first_dof + i, ns_ + v.first_dof + j, Kv(i, j));
    }
    K_.resize(ns_ + nv_, ns_ + nv_);
    K_.setFromTriplets(base_.begin(), base_.end());
  }

  Status solve(const StepProblem& p, StepSolution& s) override {
    const int n = ns_ + nv_ + nc_;
    if (z_.size() != n) z_ = Vector::Zero(n);
    z_.tail(nc_) = s.P;
    s.iterations = 0;
    if (Status st = newton(p, s.iterations); !st.ok()) return st;
    s.u_s = z_.head(ns_);
    s.u_v = z_.segment(ns_, nv_);
    s.P = z_.tail(nc_);
    return Status::Ok();
  }

 private:
  double penetration(const StepProblem& p, int c) const {
    return rail_top(p.rows[c], z_, coords_) + p.r[c] - z_[ns_ + layout_.contacts[c].global_dof];
  }

  void residual(const StepProblem& p, Vector& R) const {
    const double one_alpha = 1.0 + options_.alpha;
    const Vector u = z_.head(ns_ + nv_);
    R.resize(z_.size());
    R.head(ns_ + nv_) = K_ * u;
    R.head(ns_) -= p.rhs_s;
    R.segment(ns_, nv_) -= p.rhs_v;
    Vector fs = Vector::Zero(ns_);
    const Vector P = z_.tail(nc_);
    add_rail_loads(p.rows, P, -one_alpha, fs, coords_);  // + (1+alpha) N^T P
    R.head(ns_) += fs;
    if (p.rigid) {
      // The wheel follows the rail: its kinematic acceleration and velocity
      // replace Newmark's in the vehicle's equations (rigid_wheels.hpp).
      const Vector u_s = z_.head(ns_);
      for (int c = 0; c < nc_; ++c) {
        const ContactSpec& cs = layout_.contacts[c];
        const auto t = static_cast<std::size_t>(c);
        const WheelDefect d = wheel_defect((*p.rigid)[t], p.rows[t], u_s, z_[ns_ + cs.global_dof], coords_);
        const VehicleInstance& v = layout_.vehicles[cs.vehicle];
        R.segment(ns_ + v.first_dof, v.model->num_dofs()) +=
            d.a * v.model->M().col(cs.local_dof) + (one_alpha * d.v) * v.model->C().col(cs.local_dof);
      }
    }
    for (int c = 0; c < nc_; ++c) {
      const ContactSpec& cs = layout_.contacts[c];
      R[ns_ + cs.global_dof] -= one_alpha * P[c];
      const double delta = penetration(p, c);
      if (cs.law->is_constraint()) R[ns_ + nv_ + c] = -delta;
      else R[ns_ + nv_ + c] = P[c] - cs.law->force(delta);
    }
  }

  Status newton(const StepProblem& p, int& iterations) {
    const double one_alpha = 1.0 + options_.alpha;
    const int n = ns_ + nv_ + nc_;
    Vector R;
    for (int it = 0; it < options_.max_iterations; ++it) {
      ++iterations;
      residual(p, R);
      std::vector<Triplet> t = base_;
      for (int c = 0; c < nc_; ++c) {
        const ContactSpec& cs = layout_.contacts[c];
        const int row = ns_ + nv_ + c;
        const int wheel = ns_ + cs.global_dof;
        if (p.rigid) add_wheel_following_jacobian(p, c, t);
        // Coupling columns: D_bar of eq. (36).
        if (p.rows[c])
          for (int k = 0; k < 4; ++k)
            if (p.rows[c]->dof[k] >= 0) t.emplace_back(p.rows[c]->dof[k], row, one_alpha * p.rows[c]->weight[k]);
        t.emplace_back(wheel, row, -one_alpha);
        // Constraint rows: H_bar of eq. (36), or the linearized contact law.
        double dn = 0.0, dp = 0.0;  // d R_c / d(delta), d R_c / dP
        if (cs.law->is_constraint()) {
          dn = -1.0;
        } else {
          dn = -cs.law->stiffness(penetration(p, c));
          dp = 1.0;
        }
        if (dp != 0.0) t.emplace_back(row, row, dp);
        if (dn != 0.0) {
          if (p.rows[c])
            for (int k = 0; k < 4; ++k)
              if (p.rows[c]->dof[k] >= 0) t.emplace_back(row, p.rows[c]->dof[k], dn * p.rows[c]->weight[k]);
          t.emplace_back(row, wheel, -dn);
        }
      }
      SparseMatrix J(n, n);
      J.setFromTriplets(t.begin(), t.end());
      lu_.compute(J);
      if (lu_.info() != Eigen::Success)
        return {StatusCode::kDiverged, "reference path: UMFPACK could not factorize eq. (36)"};
      const Vector minus_R = -R;
      const Vector dz = lu_.solve(minus_R);
      if (!dz.allFinite()) return {StatusCode::kDiverged, "reference path: non-finite Newton step"};
      z_ += dz;
      // The structure and vehicle rows are linear and now hold to round-off;
      // convergence is judged on the nonlinear (compliant) contact rows, in
      // newtons, as eq. (25). Rigid rows are linear too: one iteration is exact.
      residual(p, R);
      double contact_res = 0.0;
      for (int c = 0; c < nc_; ++c)
        if (!layout_.contacts[c].law->is_constraint()) contact_res += R[ns_ + nv_ + c] * R[ns_ + nv_ + c];
      if (std::sqrt(contact_res) <= options_.tolerance * options_.force_scale_N) return Status::Ok();
    }
    return {StatusCode::kNoConvergence,
            fmt::format("reference path: Newton did not converge in {} iterations", options_.max_iterations)};
  }

  // d/d(u_s, u_w) of M E^T d_a + (1+alpha) C E^T d_v for contact c's wheel.
  void add_wheel_following_jacobian(const StepProblem& p, int c, std::vector<Triplet>& t) const {
    const ContactSpec& cs = layout_.contacts[c];
    const WheelFollowsRail& f = (*p.rigid)[static_cast<std::size_t>(c)];
    const VehicleInstance& v = layout_.vehicles[cs.vehicle];
    const auto& row = p.rows[static_cast<std::size_t>(c)];
    const double one_alpha = 1.0 + options_.alpha;
    for (int i = 0; i < v.model->num_dofs(); ++i) {
      const double m = v.model->M()(i, cs.local_dof), cd = one_alpha * v.model->C()(i, cs.local_dof);
      if (m == 0.0 && cd == 0.0) continue;
      const int r = ns_ + v.first_dof + i;
      t.emplace_back(r, ns_ + cs.global_dof, -(m * f.c_a_u + cd * f.c_v_u));
      if (!row) continue;
      for (int k = 0; k < 4; ++k) {
        if (row->dof[k] < 0) continue;
        t.emplace_back(r, row->dof[k],
                       m * (f.c_a_u * row->weight[k] + f.c_a_slope * row->slope[k] + f.c_a_curv * row->curvature[k]) +
                           cd * (f.c_v_u * row->weight[k] + f.c_v_slope * row->slope[k]));
      }
    }
  }

  StructureCoordinates coords_;  // the model's DOFs: the bordered system is assembled on them
  const TrainLayout& layout_;
  StepSolverOptions options_;
  int ns_, nv_, nc_;
  std::vector<Triplet> base_;
  SparseMatrix K_;
  Vector z_;
  Eigen::UmfPackLU<SparseMatrix> lu_;
};

}  // namespace

std::unique_ptr<StepSolver> make_reference_step_solver(const StructureModel& structure,
                                                       const EffectiveMatrixFactors& factors,
                                                       const TrainLayout& layout,
                                                       const HhtCoefficients& h,
                                                       const StepSolverOptions& options) {
  return std::make_unique<ReferenceStepSolver>(structure, factors, layout, h, options);
}

}  // namespace railvsi
