// Isolated track defects: the cosine dip and bump of the scene format,
// checked against the formula evaluated here with std::cos.
#include <cmath>
#include <memory>
#include <numbers>

#include <gtest/gtest.h>

#include "core/input_error.hpp"
#include "generators/track_defect.hpp"

namespace railvsi {
namespace {

double cosine_shape(double x, double x0, double L, double d) {
  const double s = (x - x0) / L;
  return s >= 0.0 && s <= 1.0 ? 0.5 * d * (1.0 - std::cos(2.0 * std::numbers::pi * s)) : 0.0;
}

TEST(TrackDefect, DipReachesMinusDepthAtItsCentreAndIsZeroOutside) {
  const double x0 = 30.0, L = 1.2, d = 0.004;
  const Irregularity p = with_defects(nullptr, {{DefectShape::kDip, x0, L, d}});
  EXPECT_NEAR(p.at(x0 + 0.5 * L), -d, 1e-15);
  double min_r = 0.0;
  for (double r : p.r_m()) min_r = std::min(min_r, r);
  EXPECT_NEAR(min_r, -d, 1e-15);
  for (double x : {x0 - 5.0, x0 - 1e-6, x0, x0 + L, x0 + L + 1e-6, x0 + 10.0}) EXPECT_NEAR(p.at(x), 0.0, 1e-18) << x;
  for (double s : {0.1, 0.25, 0.37, 0.8})  // linear between 65 samples: within 0.13 % of d
    EXPECT_NEAR(p.at(x0 + s * L), -cosine_shape(x0 + s * L, x0, L, d), 1.3e-3 * d) << s;
  EXPECT_NE(p.source().find("dip 0.004 m deep, 1.2 m long at x = 30 m"), std::string::npos) << p.source();
}

TEST(TrackDefect, BumpRaisesTheRailAndOverlappingDefectsAdd) {
  const Irregularity p = with_defects(nullptr, {{DefectShape::kBump, 10.0, 2.0, 0.003}, {DefectShape::kDip, 10.5, 1.0, 0.001}});
  EXPECT_NEAR(p.at(11.0), 0.003 - 0.001, 1e-15);
  EXPECT_NEAR(p.at(10.5), cosine_shape(10.5, 10.0, 2.0, 0.003), 1e-15);
  EXPECT_EQ(p.at(12.5), 0.0);
}

TEST(TrackDefect, AddsToABaseProfileAtTheBaseSamplesAndItsOwn) {
  const auto base = std::make_shared<const Irregularity>(std::vector<double>{0.0, 10.0, 20.0},
                                                         std::vector<double>{0.0, 0.002, 0.0}, "measured");
  const Irregularity p = with_defects(base.get(), {{DefectShape::kDip, 9.0, 2.0, 0.001}});
  EXPECT_NEAR(p.at(10.0), 0.002 - 0.001, 1e-15);
  EXPECT_NEAR(p.at(5.0), 0.001, 1e-15);
  EXPECT_NEAR(p.at(9.0), 0.0018, 1e-15);  // the base alone at the defect's start
  EXPECT_EQ(p.at(25.0), 0.0);
  EXPECT_EQ(p.source(), "measured; dip 0.001 m deep, 2 m long at x = 9 m");
}

std::string error_path(const Irregularity* base, const TrackDefect& d) {
  try {
    with_defects(base, {{DefectShape::kDip, 0.0, 1.0, 0.001}, d});
  } catch (const InputError& e) {
    return e.json_path();
  }
  return "(accepted)";
}

TEST(TrackDefect, RejectsNonPositiveDepthOrLengthAndDefectsOffTheBaseProfile) {
  EXPECT_EQ(error_path(nullptr, {DefectShape::kDip, 5.0, 1.0, -0.001}), "/defects/1/depth_m");
  EXPECT_EQ(error_path(nullptr, {DefectShape::kBump, 5.0, 1.0, 0.0}), "/defects/1/depth_m");
  EXPECT_EQ(error_path(nullptr, {DefectShape::kBump, 5.0, 0.0, 0.001}), "/defects/1/length_m");
  const Irregularity base({-1.0, 8.0}, {0.0, 0.0});
  EXPECT_EQ(error_path(&base, {DefectShape::kDip, 7.5, 1.0, 0.001}), "/defects/1/x_m");
  EXPECT_EQ(error_path(&base, {DefectShape::kDip, 6.5, 1.0, 0.001}), "(accepted)");
}

}  // namespace
}  // namespace railvsi
