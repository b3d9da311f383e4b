#pragma once
// Rigid contact with the wheel's vertical DOF eliminated: the wheel follows
// the rail top under it,
//   u_w = N u_s + r,
//   v_w = N v_s + V (N' u_s + r'),
//   a_w = N a_s + 2 V N' v_s + V^2 (N'' u_s + r''),
// (N, N', N'' the Hermite row at the moving contact point x = x0 + V t and
// its x-derivatives; r from the profile's C2 spline). The wheel's inertia and
// suspension forces then act on the structure through the contact point, and
// the contact force is what the wheel's HHT equation of motion needs.
//
// Why: imposing only u_w = N u_s + r (an index-3 constraint) leaves the
// wheel's velocity and acceleration to Newmark's recursion on a prescribed
// displacement sequence, whose homogeneous part has the eigenvalue -1 (a
// Jordan block at alpha = 0: linear growth; near -1 for alpha < 0). Every
// kink of the moving contact point excites it and the force alternates
// sign from step to step. With the wheel's state defined by the structure's
// state, no such mode exists: for a contact point at rest the eliminated
// system is one linear mechanical system (structure + wheel mass + the rest
// of the vehicle) with symmetric, positive M, C, K, for which HHT with
// alpha in [-1/3, 0] and the consistent beta, gamma is unconditionally
// stable (Hilber, Hughes & Taylor 1977); a moving point adds the bounded
// convective terms of a moving mass.
//
// How it is solved: the step keeps the displacement constraint delta = 0 and
// the contact force as unknown; the wheel's HHT equation uses the kinematic
// a_w, v_w instead of Newmark's. They differ from Newmark's values by terms
// affine in the new structure and wheel displacements,
//   d_a = c_a_u (N u_s - u_w) + c_a_slope N' u_s + c_a_curv N'' u_s + a_known,
//   d_v = c_v_u (N u_s - u_w) + c_v_slope N' u_s + v_known,
// which enter the vehicle equations as -M E^T d_a - (1+alpha) C E^T d_v.
// After each step (and at t = 0) the wheel's state is set to the kinematic
// one (follow_rail), so both solver paths solve the same discrete equations.
#include <optional>
#include <vector>

#include "integration/hht.hpp"
#include "model/rail_line.hpp"
#include "simulation/evaluation_window.hpp"
#include "simulation/result.hpp"
#include "simulation/scene.hpp"
#include "simulation/train_layout.hpp"
#include "solver/structure_coordinates.hpp"

namespace railvsi {

struct WheelFollowsRail {
  double c_a_u = 0.0, c_a_slope = 0.0, c_a_curv = 0.0, a_known = 0.0;
  double c_v_u = 0.0, c_v_slope = 0.0, v_known = 0.0;
};

// d_a and d_v of one wheel for given structure and wheel displacements.
struct WheelDefect {
  double a = 0.0, v = 0.0;
};
WheelDefect wheel_defect(const WheelFollowsRail& t, const std::optional<RailContactRow>& row,
                         const Vector& u_s, double u_w, const StructureCoordinates& coords);

// Rigid contact needs HHT's numerical damping where wheels have mass: at
// alpha = 0 a wheel mass moving over the rail's beam elements excites the
// rail's highest modes parametrically (at the element-crossing frequency)
// and nothing damps them. Measured on the TTB-2D-like span with 0.3 m rail
// elements, ICE3 at 300 km/h: alpha = 0 gave a wheel-force range of 85 kN at
// dt = 0.25 ms and step-to-step sign changes at 0.125 ms (Hertz: 19.6 kN);
// alpha = -0.02 gave 19.3 kN. Throws InputError (/analysis/hht_alpha) for
// alpha > -0.02 with a rigid law and a wheel of non-zero mass.
void check_rigid_contact_alpha(const TrainLayout& layout, double alpha);
constexpr double kRigidMaxAlpha = -0.02;

class RigidWheels {
 public:
  // Structure states in the coordinates `coords` (referenced).
  RigidWheels(const Scene& scene, const TrainLayout& layout, const StructureCoordinates& coords);
  // True when the scene's contacts are rigid (then every term below applies).
  bool enabled() const { return enabled_; }

  // Before the step to front_x_m: the profile under each wheel (overwrites r
  // with the spline value) and the terms of d_a, d_v from the states at t_n.
  void prepare(const HhtCoefficients& h, double front_x_m, const KinematicState& structure,
               const std::vector<KinematicState>& vehicles,
               const std::vector<std::optional<RailContactRow>>& rows, Vector& r);
  const std::vector<WheelFollowsRail>& terms() const { return terms_; }

  // The wheels' states := the rail top's under them (structure state at the
  // same time, rows located at front_x_m). After a step (after_step), also
  // records where a wheel crossed a slope discontinuity of its path: a node
  // whose two elements have different rotation DOFs (a joint at a pier), or
  // the passage between the rigid path and a line (a rail end, the bridge
  // end without track). Its velocity jumps there by V times the kink.
  void follow_rail(double front_x_m, const KinematicState& structure,
                   const std::vector<std::optional<RailContactRow>>& rows,
                   std::vector<KinematicState>& vehicles, bool after_step = false, double t_s = 0.0);

  // rigid_path_kink: a rigid wheel crossed a kink of its path. Its velocity
  // jumps there; the impulse m dv of that jump is not a force any step can
  // carry, so the wheel force and the structure miss it.
  // Only kinks inside the evaluation window count (the embankments' rail
  // ends are not bridge results).
  void add_warnings(std::vector<RunWarning>& warnings) const;

 private:
  ProfilePoint profile(double front_x_m, const ContactSpec& c) const;

  const Scene& scene_;
  const TrainLayout& layout_;
  const StructureCoordinates& coords_;
  bool enabled_ = false;
  std::vector<WheelFollowsRail> terms_;
  struct Kink {
    double impulse_Ns = 0.0, dv_mps = 0.0, t_s = 0.0;
    int contact = -1;
  };
  Kink worst_;  // largest unresolved impulse of the run, in the window
  std::vector<std::optional<RailContactRow>> rows_prev_;
  EvaluationWindow window_;
};

}  // namespace railvsi
