// An imported model given neither damping nor a C matrix runs undamped: the
// warning each of its runs carries (code structure_undamped) and vsi
// validate prints at /structure/damping.
#pragma once

#include <string_view>

#include "model/structure_model.hpp"

namespace railvsi {

inline bool structure_undamped(const StructureInfo& info) { return info.damping_source == "none"; }

inline constexpr std::string_view kUndampedStructureWarning =
    "no damping given and no C matrix imported: the structure runs undamped (0 %), which overstates a resonance "
    "about twice; EN 1991-2 6.4.6.3.1 prescribes the lower bound of Table 6.6: give damping.en1991.bridge_type "
    "(or damping.ratio) with f1_hz and f2_hz";

}  // namespace railvsi
