#pragma once
// Normal wheel-rail contact laws, P = H(delta), delta > 0 compression.
//   rigid:        delta = 0 while in contact (a constraint, no H)
//   linear-hertz: P = P0 + k_H (delta - delta0), linearized at the static load
//   hertz:        P = n (delta/G)^(3/2) for delta > 0, else 0
// A unilateral law never returns a tensile force.
#include "simulation/scene.hpp"

namespace railvsi {

struct ContactLawPoint {
  ContactLaw law = ContactLaw::kHertz;
  bool unilateral = true;
  double G = 0.0;          // m/N^(2/3)
  double n = 1.0;          // wheels sharing the contact
  double P0_N = 0.0;       // static load (linear-hertz)
  double delta0_m = 0.0;   // static compression (linear-hertz)
  double k_N_per_m = 0.0;  // linearized stiffness (linear-hertz)

  bool is_rigid() const { return law == ContactLaw::kRigid; }
  // Force and its derivative dP/d(delta) for a compliant law.
  double force(double delta_m) const;
  double stiffness(double delta_m) const;
  // Compression under a given load (static equilibrium): the inverse law.
  double compression(double P_N) const;
  double compliance(double P_N) const;  // d(delta)/dP
  // Fix the linearization of linear-hertz at the static load P0.
  void linearize_at(double P0);
};

}  // namespace railvsi
