#pragma once
// JobEnvelopes as (quantity, location, value) rows: the shape of the result
// store's envelopes table. Quantity names carry the unit; location is an
// output point, a wheel, or "" for the whole job. An absent value (no
// number could be produced) is a row with no value, never a NaN.
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "envelopes/job_envelopes.hpp"

namespace railvsi {

// Which end of a quantity governs: the largest unloading, the smallest
// contact force.
enum class Extreme { kMax, kMin };

struct EnvelopeQuantity {
  std::string_view name;
  Extreme extreme;
  std::string_view description;
};

// Every quantity envelope_rows() writes, in that order.
const std::vector<EnvelopeQuantity>& envelope_quantities();
// nullopt for a name that is not an envelope quantity.
std::optional<Extreme> extreme_of(std::string_view quantity);

struct EnvelopeRow {
  std::string quantity;
  std::string location;
  std::optional<double> value;
};

// Deck rows for every output point and overall; wheel and car-body rows
// only for a train with wheels (moving forces have none), per wheel only
// for the wheels inside the evaluation window; Newton iterations. Values
// absent in the envelopes give rows without a value.
std::vector<EnvelopeRow> envelope_rows(const JobEnvelopes& envelopes);

}  // namespace railvsi
