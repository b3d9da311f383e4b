// The condensed direct method (README "The method", steps 1-5; the direct
// method of Neves et al. (2014), Eng. Struct. 69, section 3).
#include <fmt/format.h>

#include "contact/contact_problem.hpp"
#include "simulation/static_equilibrium.hpp"
#include "simulation/step_solver.hpp"

namespace railvsi {
namespace {

class CondensedStepSolver final : public StepSolver {
 public:
  CondensedStepSolver(std::shared_ptr<const StructureOperator> op, const TrainLayout& layout,
                      std::vector<VehicleOperator> vehicles, const StepSolverOptions& options)
      : op_(std::move(op)), layout_(layout), vehicles_(std::move(vehicles)), options_(options),
        ws_(op_->make_workspace()) {
    const auto nc = static_cast<Eigen::Index>(layout_.contacts.size());
    A_.resize(nc, nc);
    delta_bar_.resize(nc);
    for (const ContactSpec& c : layout_.contacts) laws_.push_back(c.law);
  }

  Status solve(const StepProblem& p, StepSolution& s) override {
    const double one_alpha = 1.0 + options_.alpha;
    // 1. Free prediction with the new contact forces set to zero.
    if (Status st = op_->solve(p.rhs_s, s.u_s, *ws_); !st.ok()) return st;
    s.u_v.resize(layout_.num_vehicle_dofs);
    for (const VehicleInstance& v : layout_.vehicles) {
      const int n = v.model->num_dofs();
      s.u_v.segment(v.first_dof, n) = vehicles_[v.type].factor.solve(p.rhs_v.segment(v.first_dof, n));
    }
    const auto nc = static_cast<Eigen::Index>(layout_.contacts.size());
    s.iterations = 0;
    if (nc == 0) return Status::Ok();

    // 2-3. Penetration affine in P: delta = delta_bar - (1+alpha) A P.
    bool any_on_track = false;
    for (Eigen::Index c = 0; c < nc; ++c) {
      const ContactSpec& cs = layout_.contacts[c];
      delta_bar_[c] = rail_top(p.rows[c], s.u_s) + p.r[c] - s.u_v[cs.global_dof];
      any_on_track = any_on_track || p.rows[c].has_value();
    }
    assemble_A(p.rows);

    // 4. The small contact problem.
    ContactProblemOptions cpo;
    cpo.max_iterations = options_.max_iterations;
    cpo.tolerance = options_.tolerance;
    cpo.force_scale_N = options_.force_scale_N;
    ContactProblemSummary summary;
    const Status st = solve_contact_problem(delta_bar_, A_, laws_, cpo, s.P, contact_ws_, summary);
    s.iterations = summary.iterations;
    if (!st.ok()) return st;

    // 5. Back-substitution of the contact forces.
    if (any_on_track) {
      load_.setZero(op_->num_dofs());
      add_rail_loads(p.rows, s.P, one_alpha, load_);
      if (Status st2 = op_->solve(load_, correction_, *ws_); !st2.ok()) return st2;
      s.u_s += correction_;
    }
    for (Eigen::Index c = 0; c < nc; ++c) {
      const ContactSpec& cs = layout_.contacts[c];
      const VehicleInstance& v = layout_.vehicles[cs.vehicle];
      s.u_v.segment(v.first_dof, v.model->num_dofs()) +=
          (one_alpha * s.P[c]) * vehicles_[v.type].wheel_columns.col(cs.local_wheel);
    }
    return Status::Ok();
  }

 private:
  // (1+alpha) (N F_s N^T + E F_v E^T), F_s the rail flexibility.
  void assemble_A(const std::vector<std::optional<RailContactRow>>& rows) {
    const auto nc = A_.rows();
    const DenseMatrix& F = op_->rail_flexibility();
    for (Eigen::Index c = 0; c < nc; ++c) {
      for (Eigen::Index e = c; e < nc; ++e) {
        double a = 0.0;
        if (rows[c] && rows[e]) {
          for (int i = 0; i < 4; ++i) {
            const int di = rows[c]->dof[i];
            if (di < 0) continue;
            const int ri = op_->rail_index(di);
            for (int j = 0; j < 4; ++j) {
              const int dj = rows[e]->dof[j];
              if (dj >= 0) a += rows[c]->weight[i] * rows[e]->weight[j] * F(ri, op_->rail_index(dj));
            }
          }
        }
        const ContactSpec& cc = layout_.contacts[c];
        const ContactSpec& ce = layout_.contacts[e];
        if (cc.vehicle == ce.vehicle)
          a += vehicles_[layout_.vehicles[cc.vehicle].type].wheel_flexibility(cc.local_wheel, ce.local_wheel);
        A_(c, e) = A_(e, c) = (1.0 + options_.alpha) * a;
      }
    }
  }

  std::shared_ptr<const StructureOperator> op_;
  const TrainLayout& layout_;
  std::vector<VehicleOperator> vehicles_;
  StepSolverOptions options_;
  std::unique_ptr<SolveWorkspace> ws_;
  std::vector<ContactLawPoint> laws_;
  DenseMatrix A_;
  Vector delta_bar_, load_, correction_;
  ContactWorkspace contact_ws_;
};

}  // namespace

std::unique_ptr<StepSolver> make_condensed_step_solver(std::shared_ptr<const StructureOperator> op,
                                                       const TrainLayout& layout,
                                                       std::vector<VehicleOperator> vehicles,
                                                       const StepSolverOptions& options) {
  return std::make_unique<CondensedStepSolver>(std::move(op), layout, std::move(vehicles), options);
}

}  // namespace railvsi
