#include "contact/contact_law.hpp"

#include <algorithm>
#include <cmath>

namespace railvsi {

double hertz_constant(const ContactOptions& c, double wheel_radius_m) {
  if (c.hertz_G) return *c.hertz_G;
  return 3.86e-8 * std::pow(wheel_radius_m, -0.115);
}

double ContactLawPoint::force(double d) const {
  switch (law) {
    case ContactLaw::kHertz:
      return d > 0.0 ? n * std::pow(d / G, 1.5) : 0.0;
    case ContactLaw::kLinearHertz: {
      const double P = P0_N + k_N_per_m * (d - delta0_m);
      return unilateral ? std::max(0.0, P) : P;
    }
    case ContactLaw::kRigid:
      break;
  }
  return 0.0;
}

double ContactLawPoint::stiffness(double d) const {
  switch (law) {
    case ContactLaw::kHertz:
      return d > 0.0 ? 1.5 * n * std::sqrt(d / G) / G : 0.0;
    case ContactLaw::kLinearHertz:
      return (!unilateral || P0_N + k_N_per_m * (d - delta0_m) > 0.0) ? k_N_per_m : 0.0;
    case ContactLaw::kRigid:
      break;
  }
  return 0.0;
}

double ContactLawPoint::compression(double P) const {
  if (law == ContactLaw::kRigid || P <= 0.0) return 0.0;
  return G * std::pow(P / n, 2.0 / 3.0);  // static: linear-hertz coincides with hertz
}

double ContactLawPoint::compliance(double P) const {
  if (law == ContactLaw::kRigid || P <= 0.0) return 0.0;
  return (2.0 / 3.0) * G * std::pow(n, -2.0 / 3.0) * std::pow(P, -1.0 / 3.0);
}

void ContactLawPoint::linearize_at(double P0) {
  P0_N = P0;
  delta0_m = compression(P0);
  k_N_per_m = delta0_m > 0.0 ? 1.5 * P0 / delta0_m : 0.0;
}

}  // namespace railvsi
