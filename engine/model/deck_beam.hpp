#pragma once
// The deck girder of a plane bridge as the generator built it: what section
// forces need beyond the assembled matrices. Each deck element is an
// Euler-Bernoulli beam (generators/beam_element.hpp) with these properties;
// its damping is Rayleigh, C_e = a0 M_e + a1 K_e; and the track (if any)
// bears on the deck through springs and dashpots whose forces are loads on
// the deck elements.
#include <vector>

namespace railvsi {

// A spring (and dashpot) from a track DOF onto a point of the deck:
// force on the deck, upward, k (u_dof - w(x) u_deck) + c (v_dof - w(x) v_deck).
struct DeckLink {
  int dof = -1;
  double x_m = 0.0;
  double k_N_per_m = 0.0;
  double c_Ns_per_m = 0.0;
};

struct DeckBeam {
  double EI_Nm2 = 0.0;
  double mass_kg_per_m = 0.0;
  double rayleigh_a0_per_s = 0.0;
  double rayleigh_a1_s = 0.0;
  std::vector<DeckLink> links;
};

}  // namespace railvsi
