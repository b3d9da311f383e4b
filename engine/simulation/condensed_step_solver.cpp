// The condensed direct method (docs/method.md, steps 1-5; the direct
// method of Neves et al. (2014), Eng. Struct. 69, section 3).
#include <array>
#include <fmt/format.h>

#include "contact/contact_problem.hpp"
#include "simulation/static_equilibrium.hpp"
#include "simulation/step_solver.hpp"

namespace railvsi {
namespace {

class CondensedStepSolver final : public StepSolver {
 public:
  CondensedStepSolver(std::shared_ptr<const StructureOperator> op, const StructureCoordinates& coords,
                      const TrainLayout& layout, std::vector<VehicleOperator> vehicles,
                      const StepSolverOptions& options)
      : op_(std::move(op)), coords_(coords), layout_(layout), vehicles_(std::move(vehicles)), options_(options),
        ws_(op_->make_workspace()) {
    const auto nc = static_cast<Eigen::Index>(layout_.contacts.size());
    A_.resize(nc, nc);
    delta_bar_.resize(nc);
    for (const ContactSpec& c : layout_.contacts) laws_.push_back(c.law.get());
  }

  Status solve(const StepProblem& p, StepSolution& s) override {
    const double one_alpha = 1.0 + options_.alpha;
    // 1. Free prediction with the new contact forces set to zero: the
    // structure's only at the rail DOFs (the split solve,
    // StructureOperator::forward), the vehicles' whole.
    if (Status st = op_->forward(p.rhs_s, y_, *ws_); !st.ok()) return st;
    s.u_v.resize(layout_.num_vehicle_dofs);
    for (const VehicleInstance& v : layout_.vehicles) {
      const int n = v.model->num_dofs();
      s.u_v.segment(v.first_dof, n) = vehicles_[v.type].factor.solve(p.rhs_v.segment(v.first_dof, n));
    }
    const auto nc = static_cast<Eigen::Index>(layout_.contacts.size());
    s.iterations = 0;
    bool any_on_track = false;
    for (Eigen::Index c = 0; c < nc; ++c) any_on_track = any_on_track || p.rows[c].has_value();
    if (!any_on_track) {
      // No load on the structure's rails: its displacement is the free one.
      if (Status st = op_->backward(y_, s.u_s, *ws_); !st.ok()) return st;
      if (nc == 0) return Status::Ok();
    } else if (Status st = op_->rail_solution(y_, s.u_s, *ws_); !st.ok()) {
      return st;
    }

    // 2-3. Penetration affine in P: delta = delta_bar - A P. With a
    // residual flexibility R (the modal backend's dropped modes), the rail
    // under the wheels also moves by R f_{n+1}, f_{n+1} = -N^T P the rail
    // loads at t_{n+1}: A gains N R N^T, at weight 1 (quasi-static, at
    // t_{n+1}, not HHT-shifted). delta_bar would gain R times the known
    // rail loads, but a train of vehicles has none (Train: moving forces
    // or vehicles). Not on the rigid path: its wheels follow the rail's
    // slope and curvature from the state, which has no residual part.
    assemble_A(p.rows, p.rigid ? nullptr : op_->rail_residual_flexibility());
    if (p.rigid) add_wheel_following(p, s);
    for (Eigen::Index c = 0; c < nc; ++c) {
      const ContactSpec& cs = layout_.contacts[c];
      delta_bar_[c] = rail_top(p.rows[c], s.u_s, coords_) + p.r[c] - s.u_v[cs.global_dof];
    }

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
      add_rail_loads(p.rows, s.P, one_alpha, load_, coords_);
      op_->add_rail_forward(load_, y_, *ws_);
      if (Status st2 = op_->backward(y_, s.u_s, *ws_); !st2.ok()) return st2;
    }
    for (Eigen::Index c = 0; c < nc; ++c) {
      const ContactSpec& cs = layout_.contacts[c];
      const VehicleInstance& v = layout_.vehicles[cs.vehicle];
      s.u_v.segment(v.first_dof, v.model->num_dofs()) +=
          (one_alpha * s.P[c]) * vehicles_[v.type].wheel_columns.col(cs.local_wheel);
    }
    if (p.rigid) {
      // The wheels' kinematic terms at the final structure displacement,
      // in place of those of the free prediction.
      for (Eigen::Index c = 0; c < nc; ++c) {
        const auto t = static_cast<std::size_t>(c);
        const WheelDefect d = wheel_defect((*p.rigid)[t], p.rows[t], s.u_s,
                                           rail_top(p.rows[t], s.u_s, coords_) + p.r[c], coords_);
        add_vehicle_defect(c, d.a - defect_[t].a, d.v - defect_[t].v, s.u_v);
      }
    }
    return Status::Ok();
  }

 private:
  // (1+alpha) (N F_s N^T + E F_v E^T) + N R N^T, F_s the rail flexibility,
  // R the residual one (null: none). The 4 x 4 blocks of F_s (and R) under
  // two contacts are kept from step to step and read from the large
  // flexibility matrices only for the DOFs a contact has newly reached (one
  // node when it moves on to the next rail element); the sums are the same,
  // term by term.
  void assemble_A(const std::vector<std::optional<RailContactRow>>& rows, const DenseMatrix* R) {
    refresh_blocks(rows, R);
    if (R) add_pairs<true>(rows);
    else add_pairs<false>(rows);
  }

  // Two partners e, e + 1 of contact c at once, one SIMD lane each: a lane
  // does its pair's scalar sum in the same order. A DOF a lane's contact
  // lacks (or a lane past the last contact) gets weight 0 and block entry 0
  // (refresh_blocks), so its terms are +-0, which leave a sum started at +0
  // exactly as it was: A is the same bit for bit as one pair at a time.
  template <bool kResidual>
  void add_pairs(const std::vector<std::optional<RailContactRow>>& rows) {
    using Two = double __attribute__((vector_size(2 * sizeof(double))));
    const auto nc = A_.rows();
    const auto lane_weights = [&](Eigen::Index e, std::array<double, 4>& w) {
      for (int j = 0; j < 4; ++j) w[j] = e < nc && rows[e] && rows[e]->dof[j] >= 0 ? rows[e]->weight[j] : 0.0;
    };
    static const PairBlock kZero{};
    for (Eigen::Index c = 0; c < nc; ++c) {
      for (Eigen::Index e = c; e < nc; e += 2) {
        Two a{0.0, 0.0}, residual{0.0, 0.0};
        if (rows[c]) {
          std::array<double, 4> w0{}, w1{};
          lane_weights(e, w0);
          lane_weights(e + 1, w1);
          const PairBlock& b0 = blocks_[static_cast<std::size_t>(c * nc + e)];
          const PairBlock& b1 = e + 1 < nc ? blocks_[static_cast<std::size_t>(c * nc + e + 1)] : kZero;
          for (int i = 0; i < 4; ++i) {
            if (rows[c]->dof[i] < 0) continue;
            const double wi = rows[c]->weight[i];
            for (int j = 0; j < 4; ++j) {
              const Two w = Two{wi, wi} * Two{w0[j], w1[j]};
              a += w * Two{b0.F[i][j], b1.F[i][j]};
              if constexpr (kResidual) residual += w * Two{b0.R[i][j], b1.R[i][j]};
            }
          }
        }
        for (int l = 0; l < 2 && e + l < nc; ++l) {
          const Eigen::Index f = e + l;
          double al = a[l];
          const ContactSpec& cc = layout_.contacts[c];
          const ContactSpec& cf = layout_.contacts[f];
          if (cc.vehicle == cf.vehicle)
            al += vehicles_[layout_.vehicles[cc.vehicle].type].wheel_flexibility(cc.local_wheel, cf.local_wheel);
          A_(c, f) = A_(f, c) = (1.0 + options_.alpha) * al + residual[l];
        }
      }
    }
  }

  // The blocks of the pairs with a contact on other DOFs than at the last
  // step (all at the first step): entries at DOFs both contacts had are
  // moved within the block, the others read.
  void refresh_blocks(const std::vector<std::optional<RailContactRow>>& rows, const DenseMatrix* R) {
    const auto nc = static_cast<std::size_t>(A_.rows());
    blocks_.resize(nc * nc);
    constexpr std::array<int, 4> kNone{-1, -1, -1, -1};
    if (dofs_.size() != nc) dofs_.assign(nc, kNone);
    moved_.assign(nc, 0);
    kept_.resize(nc);
    const bool same_R = R == blocks_R_;
    for (std::size_t c = 0; c < nc; ++c) {
      const std::array<int, 4> now = rows[c] ? rows[c]->dof : kNone;
      moved_[c] = !same_R || now != dofs_[c];
      // Where each new DOF was in the old block (-1: to be read).
      for (int i = 0; i < 4; ++i) {
        kept_[c][i] = -1;
        for (int m = 0; m < 4 && same_R && now[i] >= 0; ++m)
          if (dofs_[c][m] == now[i]) kept_[c][i] = m;
      }
      dofs_[c] = now;
    }
    blocks_R_ = R;
    const DenseMatrix& F = op_->rail_flexibility();
    for (std::size_t c = 0; c < nc; ++c)
      for (std::size_t e = c; e < nc; ++e) {
        if (!(moved_[c] || moved_[e]) || !rows[c] || !rows[e]) continue;
        PairBlock& b = blocks_[c * nc + e];
        const PairBlock old = b;
        for (int i = 0; i < 4; ++i)
          for (int j = 0; j < 4; ++j) {
            const int di = dofs_[c][i], dj = dofs_[e][j];
            const int mi = kept_[c][i], mj = kept_[e][j];
            if (di < 0 || dj < 0) {
              b.F[i][j] = b.R[i][j] = 0.0;
            } else if (mi >= 0 && mj >= 0) {
              b.F[i][j] = old.F[mi][mj];
              b.R[i][j] = old.R[mi][mj];
            } else {
              const int ri = op_->rail_index(di), rj = op_->rail_index(dj);
              b.F[i][j] = F(ri, rj);
              b.R[i][j] = R ? (*R)(ri, rj) : 0.0;
            }
          }
      }
  }

  // u_v -= K_bar_v^-1 (M E^T da + (1+alpha) C E^T dv) for contact c's wheel.
  void add_vehicle_defect(Eigen::Index c, double da, double dv, Vector& u_v) const {
    const ContactSpec& cs = layout_.contacts[c];
    const VehicleInstance& v = layout_.vehicles[cs.vehicle];
    const VehicleOperator& vo = vehicles_[v.type];
    u_v.segment(v.first_dof, v.model->num_dofs()) -=
        da * vo.mass_columns.col(cs.local_wheel) + ((1.0 + options_.alpha) * dv) * vo.damping_columns.col(cs.local_wheel);
  }

  // Rigid contacts (rigid_wheels.hpp): the wheel's kinematic acceleration and
  // velocity depend on the rail's slope and curvature under it, which are
  // affine in P like the rail top. With the constraint u_w = N u_s + r,
  //   d_a = c_a_u (-r) + c_a_slope z' + c_a_curv z'' + a_known,  z' = N' u_s, ...
  //   d_v = c_v_u (-r) + c_v_slope z' + v_known,
  //   z' = z'_bar - (1+alpha) B1 P, z'' = z''_bar - (1+alpha) B2 P,
  //   B1 = N' F N^T, B2 = N'' F N^T,
  // and E u_v gains - G_m d_a - (1+alpha) G_c d_v (G = E K_bar_v^-1 {M, C} E^T).
  // The free prediction takes the d of the free structure displacement; A
  // gains (1+alpha) (G_m T + (1+alpha) G_c S), T = c_a_slope B1 + c_a_curv B2,
  // S = c_v_slope B1.
  void add_wheel_following(const StepProblem& p, StepSolution& s) {
    const auto nc = A_.rows();
    const double one_alpha = 1.0 + options_.alpha;
    defect_.resize(static_cast<std::size_t>(nc));
    for (Eigen::Index c = 0; c < nc; ++c) {
      const auto t = static_cast<std::size_t>(c);
      defect_[t] =
          wheel_defect((*p.rigid)[t], p.rows[t], s.u_s, rail_top(p.rows[t], s.u_s, coords_) + p.r[c], coords_);
      add_vehicle_defect(c, defect_[t].a, defect_[t].v, s.u_v);
    }
    const DenseMatrix& F = op_->rail_flexibility();
    const auto cross = [&](Eigen::Index c, Eigen::Index e, const std::array<double, 4>& wc) {
      double b = 0.0;
      if (!p.rows[c] || !p.rows[e]) return b;
      for (int i = 0; i < 4; ++i) {
        const int di = p.rows[c]->dof[i];
        if (di < 0) continue;
        const int ri = op_->rail_index(di);
        for (int j = 0; j < 4; ++j) {
          const int dj = p.rows[e]->dof[j];
          if (dj >= 0) b += wc[i] * p.rows[e]->weight[j] * F(ri, op_->rail_index(dj));
        }
      }
      return b;
    };
    T_.setZero(nc, nc);
    S_.setZero(nc, nc);
    for (Eigen::Index k = 0; k < nc; ++k) {
      if (!p.rows[k]) continue;
      const WheelFollowsRail& t = (*p.rigid)[static_cast<std::size_t>(k)];
      for (Eigen::Index e = 0; e < nc; ++e) {
        const double b1 = cross(k, e, p.rows[k]->slope), b2 = cross(k, e, p.rows[k]->curvature);
        T_(k, e) = t.c_a_slope * b1 + t.c_a_curv * b2;
        S_(k, e) = t.c_v_slope * b1;
      }
    }
    for (Eigen::Index c = 0; c < nc; ++c) {
      const ContactSpec& cc = layout_.contacts[c];
      const VehicleOperator& vo = vehicles_[layout_.vehicles[cc.vehicle].type];
      for (Eigen::Index k = 0; k < nc; ++k) {
        const ContactSpec& ck = layout_.contacts[k];
        if (ck.vehicle != cc.vehicle) continue;
        const double gm = vo.mass_columns(cc.local_dof, ck.local_wheel);
        const double gc = vo.damping_columns(cc.local_dof, ck.local_wheel);
        A_.row(c) += one_alpha * (gm * T_.row(k) + one_alpha * gc * S_.row(k));
      }
    }
  }

  std::shared_ptr<const StructureOperator> op_;
  const StructureCoordinates& coords_;
  const TrainLayout& layout_;
  std::vector<VehicleOperator> vehicles_;
  StepSolverOptions options_;
  std::unique_ptr<SolveWorkspace> ws_;
  std::vector<const ContactLaw*> laws_;
  DenseMatrix A_, T_, S_;
  Vector delta_bar_, load_, y_;  // y_: the forward image of the step's load
  std::vector<WheelDefect> defect_;  // d_a, d_v of the free prediction
  // F_s and R at the DOFs of two contacts' rail elements (rows: the first
  // contact's DOFs), for the pairs c <= e at c * nc + e.
  struct PairBlock {
    double F[4][4];
    double R[4][4];
  };
  std::vector<PairBlock> blocks_;
  std::vector<std::array<int, 4>> dofs_;  // each contact's DOFs in the blocks (-1: none)
  std::vector<std::array<int, 4>> kept_;  // scratch: a new DOF's place among the old ones
  std::vector<char> moved_;
  const DenseMatrix* blocks_R_ = nullptr;
  ContactWorkspace contact_ws_;
};

}  // namespace

std::unique_ptr<StepSolver> make_condensed_step_solver(std::shared_ptr<const StructureOperator> op,
                                                       const StructureCoordinates& coords,
                                                       const TrainLayout& layout,
                                                       std::vector<VehicleOperator> vehicles,
                                                       const StepSolverOptions& options) {
  return std::make_unique<CondensedStepSolver>(std::move(op), coords, layout, std::move(vehicles), options);
}

}  // namespace railvsi
