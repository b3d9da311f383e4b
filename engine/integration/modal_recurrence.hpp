#pragma once
// Exact time stepping of one modal equation
//   q'' + 2 zeta omega q' + omega^2 q = p(t)
// for a load p that varies linearly within each step (the load of moving
// forces sampled at the steps). The step is the exact solution of the
// linear ODE, so it has no period error and no numerical damping at any
// omega*dt: the time step only samples the load and the output. This is
// the recurrence of Nigam & Jennings (1969), "Calculation of response
// spectra from strong-motion earthquake records", BSSA 59(2), here obtained
// from the exponential of the augmented matrix [[F, g, 0], [0, 0, 1],
// [0, 0, 0]] (state q, q', load p, load rate p'), which holds for any
// damping ratio, under- or overdamped.
namespace railvsi {

struct ModalStep {
  // [q, q']_{n+1} = Phi [q, q']_n + G0 p_n + G1 (p_{n+1} - p_n) / dt;
  // g1_per_dt = G1 / dt (the step's length folded in once).
  double phi[2][2] = {{1.0, 0.0}, {0.0, 1.0}};
  double g0[2] = {0.0, 0.0};
  double g1_per_dt[2] = {0.0, 0.0};
  double omega = 0.0, zeta = 0.0;

  // One step; returns the acceleration at the end of the step, exact from
  // the equation itself. The load's part does not depend on the state, so
  // it is summed first: the state's own chain is one product and two sums.
  double advance(double& q, double& qd, double p_n, double p_next) const {
    const double change = p_next - p_n;
    const double load_q = g0[0] * p_n + g1_per_dt[0] * change;
    const double load_qd = g0[1] * p_n + g1_per_dt[1] * change;
    const double q1 = (phi[0][0] * q + phi[0][1] * qd) + load_q;
    const double qd1 = (phi[1][0] * q + phi[1][1] * qd) + load_qd;
    q = q1;
    qd = qd1;
    return p_next - 2.0 * zeta * omega * qd1 - omega * omega * q1;
  }
};

// omega >= 0 (rad/s), zeta >= 0, dt > 0.
ModalStep make_modal_step(double omega_rad_s, double zeta, double dt_s);

}  // namespace railvsi
