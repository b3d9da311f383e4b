#include "simulation/rigid_wheels.hpp"

#include <cmath>
#include <fmt/format.h>

#include "core/input_error.hpp"

namespace railvsi {
namespace {

// Newmark: a_{n+1} = c0 u_{n+1} - ha, v_{n+1} = c3 u_{n+1} - hv, with ha, hv
// from the state at t_n (eqs. 16-17 of the paper).
struct NewmarkHistory {
  double ha = 0.0, hv = 0.0;
};

NewmarkHistory newmark_history(const HhtCoefficients& h, double u, double v, double a) {
  NewmarkHistory n;
  n.ha = h.c0 * u + h.c1 * v + h.c2 * a;
  n.hv = h.gamma * h.dt * n.ha - v - h.dt * (1.0 - h.gamma) * a;
  return n;
}

}  // namespace

WheelDefect wheel_defect(const WheelFollowsRail& t, const std::optional<RailContactRow>& row,
                         const Vector& u_s, double u_w, const StructureCoordinates& coords) {
  const double rel = row_value(row, &RailContactRow::weight, u_s, coords) - u_w;
  const double slope = row_value(row, &RailContactRow::slope, u_s, coords);
  const double curv = row_value(row, &RailContactRow::curvature, u_s, coords);
  return {t.c_a_u * rel + t.c_a_slope * slope + t.c_a_curv * curv + t.a_known,
          t.c_v_u * rel + t.c_v_slope * slope + t.v_known};
}

void check_rigid_contact_alpha(const TrainLayout& layout, double alpha) {
  if (layout.contacts.empty() || !layout.contacts.front().law->is_constraint() || alpha <= kRigidMaxAlpha + 1e-12)
    return;
  for (const ContactSpec& c : layout.contacts) {
    const VehicleModel& v = *layout.vehicles[static_cast<std::size_t>(c.vehicle)].model;
    if (v.M()(c.local_dof, c.local_dof) > 0.0)
      throw InputError("/analysis/hht_alpha",
                       fmt::format("rigid contact with hht_alpha = {} > {}: a wheel mass moving over the rail's "
                                   "beam elements excites the rail's highest modes at the element-crossing "
                                   "frequency, and without numerical damping they grow (wheel forces that "
                                   "chatter or are several times too large). Use hht_alpha <= {} or the "
                                   "hertz law",
                                   alpha, kRigidMaxAlpha, kRigidMaxAlpha));
  }
}

RigidWheels::RigidWheels(const Scene& scene, const TrainLayout& layout, const StructureCoordinates& coords)
    : scene_(scene), layout_(layout), coords_(coords) {
  enabled_ = !layout.contacts.empty() && layout.contacts.front().law->is_constraint();
  if (!enabled_) return;
  terms_.resize(layout.contacts.size());
  window_ = EvaluationWindow::of(scene);
}

// A wheel crossing a kink of slope d_theta at speed V jumps in velocity by
// V d_theta. Reported above 1e-3 m/s (d_theta = 1.2e-5 rad at 300 km/h; an
// impulse of ~2 N*s for a 1.8 t wheelset, which a Hertz contact would spread
// over its ~5 ms period as ~0.4 kN).
void RigidWheels::add_warnings(std::vector<RunWarning>& warnings) const {
  constexpr double kReported_mps = 1e-3;
  if (!enabled_ || worst_.contact < 0 || std::abs(worst_.dv_mps) <= kReported_mps) return;
  RunWarning w;
  w.code = "rigid_path_kink";
  w.message = fmt::format(
      "rigid contact: wheel {} crossed a kink of its path (velocity jump {:.3g} m/s, impulse {:.3g} N*s) "
      "that no contact force of a step can carry: the deck and the wheel forces miss that impulse; "
      "use hertz where a wheel runs over a slope discontinuity (a bridge end without track, a joint)",
      wheel_name(layout_.contacts[static_cast<std::size_t>(worst_.contact)]), worst_.dv_mps, worst_.impulse_Ns);
  w.t_s = worst_.t_s;
  w.wheel = worst_.contact;
  w.factor = worst_.impulse_Ns;
  warnings.push_back(std::move(w));
}

ProfilePoint RigidWheels::profile(double front_x_m, const ContactSpec& c) const {
  if (!scene_.irregularity) return {};
  return scene_.irregularity->smooth_at(TrainLayout::position_m(front_x_m, c.offset_m));
}

void RigidWheels::prepare(const HhtCoefficients& h, double front_x_m, const KinematicState& s,
                          const std::vector<KinematicState>& vehicles,
                          const std::vector<std::optional<RailContactRow>>& rows, Vector& r) {
  if (!enabled_) return;
  const double V = scene_.speed_mps;
  for (std::size_t c = 0; c < layout_.contacts.size(); ++c) {
    const ContactSpec& cs = layout_.contacts[c];
    const ProfilePoint p = profile(front_x_m, cs);
    r[static_cast<Eigen::Index>(c)] = p.r_m;
    // The structure's history terms at the rail DOFs under the wheel.
    double Nha = 0.0, Nhv = 0.0, N1hv = 0.0;
    if (const auto& row = rows[c]) {
      for (int k = 0; k < 4; ++k) {
        const int d = row->dof[k];
        if (d < 0) continue;
        const NewmarkHistory hs = newmark_history(h, coords_.at(d, s.u), coords_.at(d, s.v), coords_.at(d, s.a));
        Nha += row->weight[k] * hs.ha;
        Nhv += row->weight[k] * hs.hv;
        N1hv += row->slope[k] * hs.hv;
      }
    }
    const KinematicState& vs = vehicles[static_cast<std::size_t>(cs.vehicle)];
    const NewmarkHistory hw = newmark_history(h, vs.u[cs.local_dof], vs.v[cs.local_dof], vs.a[cs.local_dof]);
    WheelFollowsRail& t = terms_[c];
    t.c_a_u = h.c0;
    t.c_a_slope = 2.0 * V * h.c3;
    t.c_a_curv = V * V;
    t.a_known = -Nha - 2.0 * V * N1hv + V * V * p.curvature_per_m + hw.ha;
    t.c_v_u = h.c3;
    t.c_v_slope = V;
    t.v_known = -Nhv + V * p.slope + hw.hv;
  }
}

namespace {

// Slope at the start (end = false) or end of a located element.
double element_end_slope(const RailContactRow& row, bool end, const Vector& u, const StructureCoordinates& coords) {
  return coords.at(row.dof[end ? 3 : 1], u);
}

}  // namespace

void RigidWheels::follow_rail(double front_x_m, const KinematicState& s,
                              const std::vector<std::optional<RailContactRow>>& rows,
                              std::vector<KinematicState>& vehicles, bool after_step, double t_s) {
  if (!enabled_) return;
  const double V = scene_.speed_mps;
  for (std::size_t c = 0; c < layout_.contacts.size(); ++c) {
    const ContactSpec& cs = layout_.contacts[c];
    const ProfilePoint p = profile(front_x_m, cs);
    const auto& row = rows[c];
    KinematicState& w = vehicles[static_cast<std::size_t>(cs.vehicle)];
    const double slope_u = row_value(row, &RailContactRow::slope, s.u, coords_);
    w.u[cs.local_dof] = row_value(row, &RailContactRow::weight, s.u, coords_) + p.r_m;
    w.v[cs.local_dof] = row_value(row, &RailContactRow::weight, s.v, coords_) + V * (slope_u + p.slope);
    w.a[cs.local_dof] = row_value(row, &RailContactRow::weight, s.a, coords_) +
                        2.0 * V * row_value(row, &RailContactRow::slope, s.v, coords_) +
                        V * V * (row_value(row, &RailContactRow::curvature, s.u, coords_) + p.curvature_per_m);
  }
  if (!after_step) {
    rows_prev_ = rows;
    return;
  }
  for (std::size_t c = 0; c < layout_.contacts.size(); ++c) {
    const ContactSpec& cs = layout_.contacts[c];
    const auto& now = rows[c];
    const auto& before = rows_prev_[c];
    const bool same = (now && before && now->element == before->element) || (!now && !before);
    const double x = TrainLayout::position_m(front_x_m, cs.offset_m);
    if (same || !window_.contains(x)) continue;
    // Slope left of the crossing (end of the old element, or the flat rigid
    // path) against slope right of it, both at the new state.
    const double left = before ? element_end_slope(*before, true, s.u, coords_) : 0.0;
    const double right = now ? element_end_slope(*now, false, s.u, coords_) : 0.0;
    const bool joined = before && now && before->dof[3] == now->dof[1] && before->dof[2] == now->dof[0];
    if (joined) continue;  // C1 across the node
    const double dv = scene_.speed_mps * (right - left);
    const double mass_kg = layout_.vehicles[static_cast<std::size_t>(cs.vehicle)].model->M()(cs.local_dof, cs.local_dof);
    if (std::abs(dv) > std::abs(worst_.dv_mps)) worst_ = {std::abs(dv) * mass_kg, dv, t_s, static_cast<int>(c)};
  }
  rows_prev_ = rows;
}

}  // namespace railvsi
