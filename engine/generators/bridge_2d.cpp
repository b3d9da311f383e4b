#include "generators/bridge_2d.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <numeric>
#include <fmt/format.h>

#include "core/input_error.hpp"
#include "generators/beam_element.hpp"
#include "model/rayleigh.hpp"

namespace railvsi {
namespace {

constexpr double kMergeTol_m = 1e-9;

// Triplet lists of one model under assembly; the deck's own K and M are kept
// apart so that Rayleigh damping applies to the deck only (the track has its
// own dashpots).
struct Assembly {
  int n = 0;
  std::vector<Triplet> K, M, C, K_deck, M_deck;

  int new_dof() { return n++; }
  void add_element(std::vector<Triplet>& into, const std::array<int, 4>& dofs, const Matrix4& e) {
    for (int a = 0; a < 4; ++a)
      for (int b = 0; b < 4; ++b)
        if (dofs[a] >= 0 && dofs[b] >= 0) into.emplace_back(dofs[a], dofs[b], e(a, b));
  }
  // Spring (or dashpot) of value k between u_a and the point sum w[k]*u[d[k]].
  static void add_link(std::vector<Triplet>& into, int a, const RailContactRow& row, double k) {
    into.emplace_back(a, a, k);
    for (int p = 0; p < 4; ++p) {
      if (row.dof[p] < 0) continue;
      into.emplace_back(a, row.dof[p], -k * row.weight[p]);
      into.emplace_back(row.dof[p], a, -k * row.weight[p]);
      for (int q = 0; q < 4; ++q)
        if (row.dof[q] >= 0) into.emplace_back(row.dof[p], row.dof[q], k * row.weight[p] * row.weight[q]);
    }
  }
  static void add_pair(std::vector<Triplet>& into, int a, int b, double k) {
    into.emplace_back(a, a, k);
    if (b < 0) return;  // b fixed (ground)
    into.emplace_back(b, b, k);
    into.emplace_back(a, b, -k);
    into.emplace_back(b, a, -k);
  }
};

SparseMatrix to_sparse(int n, const std::vector<Triplet>& t) {
  SparseMatrix A(n, n);
  A.setFromTriplets(t.begin(), t.end());
  A.prune(0.0);
  return A;
}

void check_options(const Bridge2dOptions& o) {
  if (o.spans_m.empty()) throw InputError("/structure/spans_m", "at least one span is needed");
  for (std::size_t i = 0; i < o.spans_m.size(); ++i)
    if (!(o.spans_m[i] > 0.0))
      throw InputError(fmt::format("/structure/spans_m/{}", i), "span length must be > 0");
  if (!(o.deck_mass_kg_per_m > 0.0)) throw InputError("/structure/deck/mass_kg_per_m", "must be > 0");
  if (o.deck_EI_Nm2 != 0.0 && o.deck_first_frequency_hz != 0.0)
    throw InputError("/structure/deck", "give either EI_Nm2 or first_frequency_hz, not both");
  if (o.deck_first_frequency_hz != 0.0) {
    if (!(o.deck_first_frequency_hz > 0.0)) throw InputError("/structure/deck/first_frequency_hz", "must be > 0");
    const auto [shortest, longest] = std::minmax_element(o.spans_m.begin(), o.spans_m.end());
    if (o.continuous && *longest - *shortest > 1e-9 * *longest)
      throw InputError("/structure/deck/first_frequency_hz",
                       "a continuous girder of unequal spans needs EI_Nm2: its first frequency is not the "
                       "simply supported frequency of its longest span, which first_frequency_hz stands for");
  } else if (o.deck_EI_Nm2 == 0.0) {
    throw InputError("/structure/deck", "give the bending stiffness EI_Nm2 or the first frequency first_frequency_hz");
  } else if (!(o.deck_EI_Nm2 > 0.0)) {
    throw InputError("/structure/deck/EI_Nm2", "must be > 0");
  }
  if (!o.damping_en1991 && !(o.damping_ratio >= 0.0 && o.damping_ratio < 1.0))
    throw InputError("/structure/damping/ratio", "must be in [0, 1)");
  if (!(o.element_length_m > 0.0)) throw InputError("/structure/element_length_m", "must be > 0");
  if (o.bearing_k_N_per_m && !(*o.bearing_k_N_per_m > 0.0))
    throw InputError("/structure/bearing_k_N_per_m", "must be > 0");
  if (o.track) {
    const TrackOptions& t = *o.track;
    const std::pair<const char*, double> positive[] = {
        {"rail_EI_Nm2", t.rail_EI_Nm2},       {"rail_mass_kg_per_m", t.rail_mass_kg_per_m},
        {"pad_k_N_per_m", t.pad_k_N_per_m},   {"sleeper_spacing_m", t.sleeper_spacing_m},
        {"sleeper_mass_kg", t.sleeper_mass_kg}, {"ballast_k_N_per_m", t.ballast_k_N_per_m},
        {"ballast_mass_kg", t.ballast_mass_kg}, {"subballast_k_N_per_m", t.subballast_k_N_per_m}};
    for (const auto& [key, value] : positive)
      if (!(value > 0.0)) throw InputError(fmt::format("/structure/track/{}", key), "must be > 0");
    const std::pair<const char*, double> non_negative[] = {
        {"pad_c_Ns_per_m", t.pad_c_Ns_per_m},
        {"ballast_c_Ns_per_m", t.ballast_c_Ns_per_m},
        {"subballast_c_Ns_per_m", t.subballast_c_Ns_per_m},
        {"approach_m", t.approach_m},
        {"exit_m", t.exit_m}};
    for (const auto& [key, value] : non_negative)
      if (!(value >= 0.0)) throw InputError(fmt::format("/structure/track/{}", key), "must be >= 0");
  }
}

}  // namespace

double simply_supported_frequency_hz(double span_m, double EI_Nm2, double mass_kg_per_m) {
  return std::numbers::pi / (2.0 * span_m * span_m) * std::sqrt(EI_Nm2 / mass_kg_per_m);
}

double simply_supported_EI_Nm2(double span_m, double frequency_hz, double mass_kg_per_m) {
  const double root = 2.0 * span_m * span_m * frequency_hz / std::numbers::pi;
  return mass_kg_per_m * root * root;
}

std::shared_ptr<const StructureModel> make_bridge_2d(const Bridge2dOptions& options) {
  check_options(options);
  Bridge2dOptions o = options;
  const double longest = *std::max_element(o.spans_m.begin(), o.spans_m.end());
  if (o.deck_first_frequency_hz > 0.0)
    o.deck_EI_Nm2 = simply_supported_EI_Nm2(longest, o.deck_first_frequency_hz, o.deck_mass_kg_per_m);
  std::string damping_source = "given";
  if (o.damping_en1991) {
    o.damping_ratio = en1991_damping_ratio(*o.damping_en1991, longest);
    damping_source = fmt::format("EN 1991-2 Table 6.6, {}, L = {} m (longest span)",
                                 en1991_bridge_type_name(*o.damping_en1991), longest);
  }
  const double total_m = std::accumulate(o.spans_m.begin(), o.spans_m.end(), 0.0);
  std::vector<std::pair<std::string, double>> outputs = o.output_points;
  for (std::size_t i = 0; i < outputs.size(); ++i)
    if (!(outputs[i].second > 0.0 && outputs[i].second < total_m))
      throw InputError(fmt::format("/outputs/points/{}/x_m", i),
                       fmt::format("deck output point must lie on the bridge (0, {})", total_m));
  if (outputs.empty()) {
    double x0 = 0.0;
    for (std::size_t s = 0; s < o.spans_m.size(); ++s) {
      outputs.emplace_back(fmt::format("span{}_mid", s + 1), x0 + 0.5 * o.spans_m[s]);
      x0 += o.spans_m[s];
    }
  }

  Assembly as;
  // ---- deck: nodes per span, merged at the piers of a continuous girder.
  std::vector<double> deck_x;                     // merged x of the deck line
  std::vector<std::array<int, 4>> deck_elements;  // per element DOFs
  int prev_v = -1, prev_rot = -1;                 // last node of the previous span (continuous)
  double x0 = 0.0;
  for (std::size_t s = 0; s < o.spans_m.size(); ++s) {
    const double L = o.spans_m[s];
    int n_el = std::max(2, static_cast<int>(std::ceil(L / o.element_length_m - 1e-9)));
    n_el += n_el % 2;  // a node at midspan
    std::vector<double> xs;
    for (int k = 0; k <= n_el; ++k) xs.push_back(x0 + L * k / n_el);
    for (const auto& p : outputs)
      if (p.second > x0 && p.second < x0 + L) xs.push_back(p.second);
    std::sort(xs.begin(), xs.end());
    xs.erase(std::unique(xs.begin(), xs.end(),
                         [](double a, double b) { return std::abs(a - b) < kMergeTol_m; }),
             xs.end());
    xs.front() = x0;
    xs.back() = x0 + L;
    std::vector<int> v(xs.size()), rot(xs.size());
    for (std::size_t i = 0; i < xs.size(); ++i) {
      const bool support = (i == 0 || i + 1 == xs.size());
      if (i == 0 && o.continuous && s > 0) {
        v[i] = prev_v;
        rot[i] = prev_rot;
        continue;
      }
      rot[i] = as.new_dof();
      if (support && !o.bearing_k_N_per_m) {
        v[i] = -1;
      } else {
        v[i] = as.new_dof();
        if (support) as.K_deck.emplace_back(v[i], v[i], *o.bearing_k_N_per_m);
      }
    }
    for (std::size_t i = 0; i + 1 < xs.size(); ++i) {
      const std::array<int, 4> dofs{v[i], rot[i], v[i + 1], rot[i + 1]};
      const double h = xs[i + 1] - xs[i];
      as.add_element(as.K_deck, dofs, beam_stiffness(o.deck_EI_Nm2, h));
      as.add_element(as.M_deck, dofs, beam_consistent_mass(o.deck_mass_kg_per_m, h));
      deck_elements.push_back(dofs);
    }
    for (std::size_t i = (s == 0 ? 0 : 1); i < xs.size(); ++i) deck_x.push_back(xs[i]);
    prev_v = v.back();
    prev_rot = rot.back();
    x0 += L;
  }
  RailLine deck_line{"deck", deck_x, deck_elements};
  const int deck_dofs = as.n;

  // Output points sit on deck nodes by construction.
  std::vector<OutputPoint> output_points;
  for (std::size_t i = 0; i < outputs.size(); ++i) {
    const auto row = deck_line.locate(outputs[i].second);
    int dof = -1;
    for (int k = 0; k < 4; ++k)
      if (row && std::abs(row->weight[k] - 1.0) < 1e-12 && (k == 0 || k == 2)) dof = row->dof[k];
    if (dof < 0)
      throw InputError(fmt::format("/outputs/points/{}/x_m", i),
                       "deck output point falls on a fixed support");
    output_points.push_back({outputs[i].first, outputs[i].second, dof});
  }

  // ---- Rayleigh damping of the deck.
  double f1 = o.damping_f1_hz, f2 = o.damping_f2_hz;
  const double f_first = simply_supported_frequency_hz(longest, o.deck_EI_Nm2, o.deck_mass_kg_per_m);
  if (f1 <= 0.0) f1 = f_first;
  if (f2 <= 0.0) f2 = std::max(30.0, 9.0 * f_first);  // f3 of a simply supported span
  DeckBeam deck_beam{o.deck_EI_Nm2, o.deck_mass_kg_per_m, 0.0, 0.0, {}};
  if (o.damping_ratio > 0.0) {
    if (!(f2 > f1)) throw InputError("/structure/damping", "f2_hz must be greater than f1_hz");
    const RayleighCoefficients r = rayleigh_coefficients(o.damping_ratio, f1, f2);
    deck_beam.rayleigh_a0_per_s = r.a0_per_s;
    deck_beam.rayleigh_a1_s = r.a1_s;
    for (const auto& t : as.M_deck) as.C.emplace_back(t.row(), t.col(), r.a0_per_s * t.value());
    for (const auto& t : as.K_deck) as.C.emplace_back(t.row(), t.col(), r.a1_s * t.value());
  }
  as.K.insert(as.K.end(), as.K_deck.begin(), as.K_deck.end());
  as.M.insert(as.M.end(), as.M_deck.begin(), as.M_deck.end());

  // ---- track: rail beam on pads, sleepers, ballast; embankments at both ends.
  std::vector<RailLine> rails;
  if (o.track) {
    const TrackOptions& t = *o.track;
    const double s = t.sleeper_spacing_m;
    const int n_approach = static_cast<int>(std::ceil(t.approach_m / s - 1e-9));
    const double x_start = -n_approach * s;
    const int n_nodes = static_cast<int>(std::ceil((total_m + t.exit_m - x_start) / s - 1e-9)) + 1;
    std::vector<double> rx(n_nodes);
    std::vector<int> rv(n_nodes), rrot(n_nodes);
    for (int k = 0; k < n_nodes; ++k) {
      rx[k] = x_start + k * s;
      // Rail ends are anchored: a wheel rolls from the rigid path onto the
      // track without a step in the support.
      rv[k] = (k == 0 || k == n_nodes - 1) ? -1 : as.new_dof();
      rrot[k] = as.new_dof();
    }
    RailLine rail = RailLine::from_nodes("rail", rx, rv, rrot);
    for (std::size_t e = 0; e < rail.num_elements(); ++e) {
      as.add_element(as.K, rail.element_dofs[e], beam_stiffness(t.rail_EI_Nm2, s));
      as.add_element(as.M, rail.element_dofs[e], beam_consistent_mass(t.rail_mass_kg_per_m, s));
    }
    for (int k = 1; k + 1 < n_nodes; ++k) {
      const int sleeper = as.new_dof();
      as.M.emplace_back(sleeper, sleeper, t.sleeper_mass_kg);
      Assembly::add_pair(as.K, rv[k], sleeper, t.pad_k_N_per_m);
      Assembly::add_pair(as.C, rv[k], sleeper, t.pad_c_Ns_per_m);
      const auto on_deck = (rx[k] >= 0.0 && rx[k] <= total_m) ? deck_line.locate(rx[k]) : std::nullopt;
      if (on_deck) {
        deck_beam.links.push_back({sleeper, rx[k], t.ballast_k_N_per_m, t.ballast_c_Ns_per_m});
        Assembly::add_link(as.K, sleeper, *on_deck, t.ballast_k_N_per_m);
        Assembly::add_link(as.C, sleeper, *on_deck, t.ballast_c_Ns_per_m);
      } else {
        const int ballast = as.new_dof();
        as.M.emplace_back(ballast, ballast, t.ballast_mass_kg);
        Assembly::add_pair(as.K, sleeper, ballast, t.ballast_k_N_per_m);
        Assembly::add_pair(as.C, sleeper, ballast, t.ballast_c_Ns_per_m);
        Assembly::add_pair(as.K, ballast, -1, t.subballast_k_N_per_m);
        Assembly::add_pair(as.C, ballast, -1, t.subballast_c_Ns_per_m);
      }
    }
    rails.push_back(std::move(rail));
  } else {
    rails.push_back(deck_line);
  }

  StructureInfo info;
  info.source = "bridge-2d";
  info.bridge_start_m = 0.0;
  info.bridge_end_m = total_m;
  info.first_frequency_hz = f_first;
  info.deck_dofs = deck_dofs;
  info.track_dofs = as.n - deck_dofs;
  info.damping_ratio = o.damping_ratio;
  info.damping_source = damping_source;
  info.deck_line = deck_line;
  info.deck_beam = std::move(deck_beam);
  info.support_x_m.push_back(0.0);
  for (const double L : o.spans_m) info.support_x_m.push_back(info.support_x_m.back() + L);
  return std::make_shared<const StructureModel>(to_sparse(as.n, as.K), to_sparse(as.n, as.M),
                                                to_sparse(as.n, as.C), std::move(rails),
                                                std::move(output_points), std::move(info));
}

}  // namespace railvsi
