#pragma once
// Lower bound of the damping ratio of railway bridges for dynamic analysis,
// EN 1991-2:2003 Table 6.6. Span L in m, zeta in percent:
//   steel and composite             0.5 + 0.125 (20 - L)  for L < 20 m, else 0.5
//   prestressed concrete            1.0 + 0.07  (20 - L)  for L < 20 m, else 1.0
//   filler beam, reinforced concrete 1.5 + 0.07 (20 - L)  for L < 20 m, else 1.5
#include <optional>
#include <string_view>

namespace railvsi {

enum class En1991BridgeType { kSteelComposite, kPrestressedConcrete, kReinforcedConcrete, kFillerBeam };

// "steel-composite", "prestressed-concrete", "reinforced-concrete", "filler-beam".
std::string_view en1991_bridge_type_name(En1991BridgeType type);
std::optional<En1991BridgeType> en1991_bridge_type_from_name(std::string_view name);

// Damping ratio as a fraction of critical (Table 6.6 gives percent).
double en1991_damping_ratio(En1991BridgeType type, double span_m);

}  // namespace railvsi
