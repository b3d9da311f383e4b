#pragma once
// Section forces, support reactions and end rotations of a beam deck
// (bridge-2d) as linear forms of the structure's state and of the loads on
// the deck: one form per quantity, so that a time step, a modal run and a
// static influence line (K g = c, Maxwell) all evaluate the same thing.
//
// Element end forces: S_e = K_e u_e + C_e v_e + M_e a_e - f_e, with f_e the
// consistent nodal loads of everything acting inside element e (the moving
// loads on the deck and the forces of the track's ballast springs). With
// f_e subtracted, S_e are the element's true end forces for Euler-Bernoulli
// beams under point loads (the FE nodal displacements are exact statically).
// Sign conventions, per section: bending moment sagging positive, shear
// V = dM/dx, reaction upward positive (traffic only: the deck's own weight is
// not in the model's loads), rotation counterclockwise (dv/dx) positive.
// Shear is evaluated on both sides of a section (a load standing exactly
// on it makes the two differ by the load), as pycba's shear points.
#include <array>
#include <string>
#include <utility>
#include <vector>

#include "core/types.hpp"
#include "model/structure_model.hpp"
#include "solver/structure_coordinates.hpp"

namespace railvsi {

// A vertical load on the deck line at x, downward positive.
struct DeckLoad {
  double x_m = 0.0;
  double down_N = 0.0;
};

// Where x falls on the deck line: the element and the Hermite weights of
// all four of its DOFs (fixed ones included); element -1 off the line.
struct DeckPoint {
  int element = -1;
  std::array<double, 4> w{0.0, 0.0, 0.0, 0.0};
};
DeckPoint deck_point(const RailLine& deck, double x_m);

struct LinearForm {
  // value = c_u.u + c_v.v + c_a.a + sum over deck loads in `element` of
  // coef . hermite_weights(x) * down_N
  std::vector<std::pair<int, double>> u, v, a;
  struct Direct {
    int element = -1;
    std::array<double, 4> coef{0.0, 0.0, 0.0, 0.0};
    // A load standing exactly on the element's first node is left out: the
    // cut just right of a section (its shear) has that load on its left.
    bool skip_at_start = false;
  };
  std::vector<Direct> direct;
  double x_m = 0.0;  // the section or support it belongs to


  double state_value(const Vector& u_s, const Vector& v_s, const Vector& a_s) const;
  // The direct term of the loads on the deck line.
  double load_value(const RailLine& deck, const std::vector<DeckLoad>& loads) const;
  // The direct term of one downward unit load at x, or at a located point.
  double unit_load_value(const RailLine& deck, double x_m) const;
  double unit_load_value(const DeckPoint& at) const;
};

struct SectionForms {
  // Why there are no forms ("" when there are).
  std::string unavailable;
  std::vector<LinearForm> forms;
  // Indexes into forms, one entry per output point of the structure.
  struct Point {
    int moment_left = -1, moment_right = -1, shear_left = -1, shear_right = -1;
  };
  std::vector<Point> points;
  // One entry per support (StructureInfo::support_x_m): the reaction (the
  // sum over the deck ends resting there) and the rotation of each deck
  // end there (two at a pier between simply supported spans).
  struct Support {
    std::string name;  // "support1", ...
    double x_m = 0.0;
    int reaction = -1;
    std::vector<int> rotations;
  };
  std::vector<Support> supports;
  // Per rail line of the structure: whether it is the deck line itself
  // (loads on it are loads on the deck elements).
  std::vector<bool> rail_is_deck;

  bool available() const { return unavailable.empty(); }
};

SectionForms make_section_forms(const StructureModel& structure);

// The forms over the coordinates of a backend whose state is not the
// model's DOFs (the hybrid structure's): each DOF term becomes that DOF's
// combination of coordinates, so that state_value() reads the run's state.
SectionForms forms_in_coordinates(SectionForms forms, const StructureCoordinates& coords);

// Envelope of the section quantities over a run: fed every step with the
// values of all forms, it writes the maxima into a RunSummary.
class SectionEnvelope {
 public:
  explicit SectionEnvelope(const SectionForms& forms);
  void update(const std::vector<double>& values);
  // Fills PointSummary::max_abs_bending_moment_Nm / max_abs_shear_force_N,
  // RunSummary::supports, or RunSummary::section_forces_note.
  void summarize(struct RunSummary& summary) const;

 private:
  const SectionForms& forms_;
  std::vector<double> moment_, shear_, reaction_, rotation_;
  bool seen_ = false;
};

}  // namespace railvsi
