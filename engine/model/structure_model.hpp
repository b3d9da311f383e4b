#pragma once
// The structure: linear and immutable once built. Boundary conditions are
// already applied (constrained DOFs are not in the matrices). Shared between
// runs and threads as shared_ptr<const StructureModel>.
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/types.hpp"
#include "model/deck_beam.hpp"
#include "model/rail_line.hpp"

namespace railvsi {

struct OutputPoint {
  std::string name;
  double x_m = 0.0;
  int dof = -1;  // vertical displacement DOF
};

// What a generator knows about the structure that the planner and the
// summary want (frequencies used for damping, where the bridge is).
struct StructureInfo {
  std::string source;            // "bridge-2d", "import"
  double bridge_start_m = 0.0;   // first support of the bridge
  double bridge_end_m = 0.0;     // last support of the bridge
  double first_frequency_hz = 0.0;  // estimate used for Rayleigh damping, 0 if unknown
  // DOFs [0, deck_dofs) are the deck's, [deck_dofs, deck_dofs + track_dofs)
  // the track's (rail, sleepers, embankment ballast).
  int deck_dofs = 0;
  int track_dofs = 0;
  // Damping ratio the structure's damping was built with (fraction of
  // critical; absent when unknown, e.g. an imported C) and where it came
  // from, for reports: "given", "EN 1991-2 Table 6.6 ...", "import C".
  std::optional<double> damping_ratio;
  std::string damping_source;
  // The deck girder as a line of beam elements and the x of its supports
  // (bridge-2d). Empty when unknown (imported models).
  RailLine deck_line;
  std::vector<double> support_x_m;
  // The deck's beam properties (bridge-2d): section forces are defined only
  // when this is present with a deck_line.
  std::optional<DeckBeam> deck_beam;
  // The track's DOFs (sorted) when they are not the range above: an imported
  // model whose map names its track nodes or DOFs. Then track_dofs is their
  // count and deck_dofs the rest.
  std::vector<int> track_dof_list;
  // What an import read and matched (one line each, for vsi inspect and
  // vsi validate) and what looks wrong without being an error.
  std::vector<std::string> import_notes;
  std::vector<std::string> import_warnings;

  bool is_track_dof(int dof) const;
};

class StructureModel {
 public:
  // Validates its arguments and throws InputError (path relative to the
  // structure document) on symmetric/mass/rail-ordering violations.
  StructureModel(SparseMatrix K, SparseMatrix M, SparseMatrix C, std::vector<RailLine> rails,
                 std::vector<OutputPoint> outputs, StructureInfo info);

  int num_dofs() const { return static_cast<int>(K_.rows()); }
  const SparseMatrix& K() const { return K_; }
  const SparseMatrix& M() const { return M_; }
  const SparseMatrix& C() const { return C_; }
  const std::vector<RailLine>& rails() const { return rails_; }
  const std::vector<OutputPoint>& outputs() const { return outputs_; }
  const StructureInfo& info() const { return info_; }
  // Sorted, unique DOFs of all rail lines: the rows/columns of the rail
  // flexibility block.
  const std::vector<int>& rail_dofs() const { return rail_dofs_; }

 private:
  SparseMatrix K_, M_, C_;
  std::vector<RailLine> rails_;
  std::vector<OutputPoint> outputs_;
  StructureInfo info_;
  std::vector<int> rail_dofs_;
};

}  // namespace railvsi
