#pragma once
// The deck's mode shapes for the report: the modes of the structure up to a
// frequency, drawn along the deck girder (bridge-2d's deck line), each
// scaled to a largest deck deflection of 1. Modes of the track alone (the
// deck barely moves) are left out, and the caption says how many.
#include <memory>
#include <optional>

#include "model/structure_model.hpp"
#include "report/compliance_report.hpp"

namespace railvsi {

// The modes up to 1.1 x max_frequency_hz; nullopt without a deck line (an
// imported model) or when the modes cannot be computed; at most max_modes
// deck modes, in ascending frequency.
std::optional<ReportFigure> deck_mode_shapes(std::shared_ptr<const StructureModel> structure, double max_frequency_hz,
                                             int max_modes);

}  // namespace railvsi
