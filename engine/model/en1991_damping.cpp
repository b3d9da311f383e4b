#include "model/en1991_damping.hpp"

#include <array>
#include <utility>

namespace railvsi {
namespace {

struct TableRow {
  En1991BridgeType type;
  std::string_view name;
  double base_percent;      // zeta for L >= 20 m
  double slope_percent_m;   // increase per metre below 20 m
};

// EN 1991-2:2003 Table 6.6.
constexpr std::array<TableRow, 4> kTable{{
    {En1991BridgeType::kSteelComposite, "steel-composite", 0.5, 0.125},
    {En1991BridgeType::kPrestressedConcrete, "prestressed-concrete", 1.0, 0.07},
    {En1991BridgeType::kReinforcedConcrete, "reinforced-concrete", 1.5, 0.07},
    {En1991BridgeType::kFillerBeam, "filler-beam", 1.5, 0.07},
}};

const TableRow& row(En1991BridgeType type) {
  for (const TableRow& r : kTable)
    if (r.type == type) return r;
  return kTable.front();
}

}  // namespace

std::string_view en1991_bridge_type_name(En1991BridgeType type) { return row(type).name; }

std::optional<En1991BridgeType> en1991_bridge_type_from_name(std::string_view name) {
  for (const TableRow& r : kTable)
    if (r.name == name) return r.type;
  return std::nullopt;
}

double en1991_damping_ratio(En1991BridgeType type, double span_m) {
  const TableRow& r = row(type);
  const double percent = span_m < 20.0 ? r.base_percent + r.slope_percent_m * (20.0 - span_m) : r.base_percent;
  return percent / 100.0;
}

}  // namespace railvsi
