#pragma once
// The code values and formulas the compliance checks use, each with the
// clause it comes from. `verified` is false for a value that was taken from
// secondary literature and not read in the standard's own text: the report
// prints it marked "unverified", never silently.
#include <string>
#include <vector>

namespace railvsi {

struct CodeValue {
  double value = 0.0;
  const char* clause = "";
  bool verified = false;
};

// EN 1990:2002+A1 A2.4.4.2.1(4)P: peak deck acceleration, frequencies up to
// max(30 Hz, 1.5 f0, f3) (the filter of results/envelopes/code_filter).
CodeValue deck_acceleration_limit_ballasted_mps2();      // 3.5
CodeValue deck_acceleration_limit_direct_fastening_mps2();  // 5.0

// EN 1991-2:2003 6.4.5.2(2), eqs. (6.4) and (6.5): dynamic factors for
// carefully maintained (Phi2) and standard maintenance (Phi3) track, of the
// determinant length L_Phi in m, clamped to their ranges.
double dynamic_factor_phi2(double determinant_length_m);
double dynamic_factor_phi3(double determinant_length_m);
inline constexpr const char* kPhiClause = "EN 1991-2 6.4.5.2(2), eqs. (6.4), (6.5)";
inline constexpr bool kPhi3Verified = true;
inline constexpr bool kPhi2Verified = false;

// EN 1991-2 Table 6.2 (cases 5.1 and 5.2): main girders simply supported,
// L_Phi = span; continuous over n spans, L_Phi = k * mean span with
// k = 1.2, 1.3, 1.4, 1.5 for n = 2, 3, 4, >= 5, and not less than the
// longest span. Unverified against the table's text.
double determinant_length_m(const std::vector<double>& spans_m, bool continuous);
inline constexpr const char* kDeterminantLengthClause = "EN 1991-2 Table 6.2, cases 5.1/5.2";

// EN 1991-2 Annex C: the additional dynamic increment of track
// irregularities, phi'' = a/100 [56 exp(-(L/10)^2) + 50 (n0 L/80 - 1)
// exp(-(L/20)^2)], a = min(v/22 m/s, 1), phi'' >= 0. Unverified.
double phi_double_prime(double determinant_length_m, double f0_hz, double speed_mps);
inline constexpr const char* kPhiDoublePrimeClause = "EN 1991-2 Annex C";

// EN 1990 A2.4.4.2.3(2): total vertical deflection under LM71 x Phi (x alpha)
// not more than L/600. Unverified.
CodeValue deflection_span_ratio();  // 600

// EN 1990 A2.4.4.3.2, Table A2.9: vertical car-body acceleration b_v for
// the levels of comfort. Unverified.
struct ComfortLevel {
  const char* name;  // "very good", "good", "acceptable"
  double b_v_mps2;
};
const std::vector<ComfortLevel>& comfort_levels();
inline constexpr const char* kComfortClause = "EN 1990 A2.4.4.3.2, Table A2.9";
inline constexpr bool kComfortVerified = false;

// EN 1990 A2.4.4.2.2: maximum deck twist over 3 m for the line speed.
// Unverified.
CodeValue twist_limit_mm_per_3m(double line_speed_kmh);

// Wheel unloading: 0.6 is common practice (e.g. the quasi-static limit of
// EN 14363), not an EN 1990 limit. Unverified.
CodeValue unloading_ratio_limit();

}  // namespace railvsi
