// The effects planner: the rung it picks for each kind of study, when it
// falls back to FE, and the escalation from linear to unilateral Hertz.
#include <gtest/gtest.h>

#include <cmath>

#include "planning/effects_planner.hpp"

namespace railvsi {
namespace {

// The 15 m span of the HSLM benchmark: f0 = 5 Hz, f3 = 45 Hz, 3 modes up to 54 Hz.
PlannerInput span_15m() {
  PlannerInput in;
  in.f0_hz = 5.0;
  in.f3_hz = 45.0;
  in.modes_below_cutoff = 3;
  return in;
}

bool ignores(const EffectsPlan& plan, std::string_view what) {
  for (const auto& i : plan.ignores)
    if (i.what.find(what) != std::string::npos) return true;
  return false;
}

TEST(EffectsPlanner, HslmDeckOnlyRunsMovingForcesOnTheModalRung) {
  const EffectsPlan plan = plan_effects(span_15m());
  EXPECT_EQ(plan.rung.name(), "moving_forces/modal");
  EXPECT_EQ(plan.rung.contact_law, "none");
  EXPECT_DOUBLE_EQ(plan.code_frequency_hz, 45.0);  // f3 sets it
  EXPECT_DOUBLE_EQ(plan.modal_cutoff_hz, 1.2 * 45.0);
  EXPECT_FALSE(plan.escalate_below_fraction);
  EXPECT_TRUE(ignores(plan, "modes above 54.0 Hz"));
  EXPECT_TRUE(ignores(plan, "vehicle dynamics"));
  EXPECT_FALSE(ignores(plan, "irregularity"));
}

TEST(EffectsPlanner, LoadModelStaysMovingForcesWhateverIsAsked) {
  PlannerInput in = span_15m();
  in.asks.wheel_unloading = in.asks.comfort = true;
  in.irregularity = true;
  const EffectsPlan plan = plan_effects(in);
  EXPECT_EQ(plan.rung.name(), "moving_forces/modal");
  EXPECT_TRUE(ignores(plan, "irregularity"));
  ASSERT_GE(plan.reasons.size(), 2u);
  EXPECT_NE(plan.reasons[1].find("no wheels"), std::string::npos);
}

TEST(EffectsPlanner, WheelUnloadingComfortOrIrregularityNeedInteractionWithLinearHertz) {
  for (int kind = 0; kind < 3; ++kind) {
    PlannerInput in = span_15m();
    in.load_model = false;
    if (kind == 0) in.asks.wheel_unloading = true;
    if (kind == 1) in.asks.comfort = true;
    if (kind == 2) in.irregularity = true;
    const EffectsPlan plan = plan_effects(in);
    EXPECT_EQ(plan.rung.model, "interaction") << kind;
    EXPECT_EQ(plan.rung.contact_law, "linear-hertz") << kind;
    EXPECT_FALSE(plan.rung.unilateral) << kind;
    ASSERT_TRUE(plan.escalate_below_fraction) << kind;
    // Wheel unloading asked: linear Hertz answers only above 70 % of the static load.
    EXPECT_DOUBLE_EQ(*plan.escalate_below_fraction, kind == 0 ? 0.7 : kEscalationFraction) << kind;
    // Interaction on the modes misses the tolerance at the planner's
    // cut-off: interaction runs on FE, and the reason says so.
    EXPECT_EQ(plan.rung.structure, "fe") << kind;
    EXPECT_EQ(plan.reasons.back(), std::string("FE structure: ") + kModalInteractionNotTrusted);
    EXPECT_NE(plan.reasons.back().find("misses the tolerance"), std::string::npos);
    EXPECT_TRUE(ignores(plan, "nonlinearity and unilaterality of Hertz"));
  }
}

TEST(EffectsPlanner, InteractionGivesItsOwnReasonForFeWhenItsModesWereNotCounted) {
  // Scene plans count the modes for moving forces only.
  PlannerInput in = span_15m();
  in.load_model = false;
  in.modes_below_cutoff = -1;
  const EffectsPlan plan = plan_effects(in);
  EXPECT_EQ(plan.rung.name(), "interaction/fe");
  EXPECT_EQ(plan.reasons.back(), std::string("FE structure: ") + kModalInteractionNotTrusted);
}

TEST(EffectsPlanner, MultibodyDeckOnlyStillNeedsTheVehicles) {
  PlannerInput in = span_15m();
  in.load_model = false;
  const EffectsPlan plan = plan_effects(in);
  EXPECT_EQ(plan.rung.model, "interaction");
  EXPECT_NE(plan.reasons.front().find("suspensions"), std::string::npos);
}

TEST(EffectsPlanner, FeWhenTheModalCutoffCannotBeHonoured) {
  PlannerInput unknown_frequencies = span_15m();
  unknown_frequencies.f3_hz = 0.0;
  PlannerInput uncounted = span_15m();
  uncounted.modes_below_cutoff = -1;
  PlannerInput too_many = span_15m();
  too_many.modes_below_cutoff = kMaxModalModes + 1;
  PlannerInput just_enough = span_15m();
  just_enough.modes_below_cutoff = kMaxModalModes;
  for (const auto* in : {&unknown_frequencies, &uncounted, &too_many}) {
    const EffectsPlan plan = plan_effects(*in);
    EXPECT_EQ(plan.rung.name(), "moving_forces/fe");
    EXPECT_EQ(plan.modal_cutoff_hz, 0.0);
    EXPECT_EQ(plan.reasons.back().rfind("FE structure: ", 0), 0u) << plan.reasons.back();
    EXPECT_FALSE(ignores(plan, "modes above"));
  }
  EXPECT_EQ(plan_effects(just_enough).rung.name(), "moving_forces/modal");
}

TEST(EffectsPlanner, CodeFrequencyIsTheLargestOfItsThreeTerms) {
  PlannerInput stiff = span_15m();
  stiff.f0_hz = 25.0;  // 1.5 f0 = 37.5 Hz governs
  stiff.f3_hz = 20.0;
  EXPECT_DOUBLE_EQ(plan_effects(stiff).code_frequency_hz, 37.5);
  PlannerInput soft = span_15m();
  soft.f0_hz = 2.0;
  soft.f3_hz = 18.0;
  EXPECT_DOUBLE_EQ(plan_effects(soft).code_frequency_hz, 30.0);
}

RunSummary two_wheels(double min_force_N) {
  RunSummary s;
  WheelSummary a, b;
  a.name = "v0_w0";
  a.static_load_N = b.static_load_N = 80000.0;
  a.min_force_N = 70000.0;
  a.evaluated = b.evaluated = true;
  b.name = "v0_w1";
  b.min_force_N = min_force_N;
  s.wheels = {a, b};
  return s;
}

TEST(EffectsPlanner, EscalatesWhenAContactForceDropsBelowTheStatedFraction) {
  EXPECT_FALSE(escalation_reason(two_wheels(40000.0), 0.5));  // exactly half: still linear
  const auto why = escalation_reason(two_wheels(39999.0), 0.5);
  ASSERT_TRUE(why);
  EXPECT_NE(why->find("wheel v0_w1"), std::string::npos);
  EXPECT_NE(why->find("50 %"), std::string::npos);
  // Contact lost (force 0) escalates; a wheel outside the evaluation window does not count.
  EXPECT_TRUE(escalation_reason(two_wheels(0.0), 0.5));
  RunSummary outside = two_wheels(0.0);
  outside.wheels[1].evaluated = false;
  EXPECT_FALSE(escalation_reason(outside, 0.5));
  // A non-finite force is not "above the fraction".
  EXPECT_TRUE(escalation_reason(two_wheels(std::nan("")), 0.5));

  PlannerInput in = span_15m();
  in.load_model = false;
  in.asks.wheel_unloading = true;
  const Rung full = escalated(plan_effects(in).rung);
  EXPECT_EQ(full.contact_law, "hertz");
  EXPECT_TRUE(full.unilateral);
  EXPECT_EQ(full.name(), "interaction/fe");
  EXPECT_FALSE(ignores(EffectsPlan{full, 0, 0, {}, rung_ignores(full, true, 0.0), {}, {}}, "Hertz"));
}

TEST(EffectsPlanner, WheelUnloadingAskedEscalatesAtHalfTheTimeStep) {
  PlannerInput wheels = span_15m();
  wheels.load_model = false;
  wheels.asks.wheel_unloading = true;
  const EffectsPlan plan = plan_effects(wheels);
  ASSERT_TRUE(plan.escalation_dt_factor);
  EXPECT_DOUBLE_EQ(*plan.escalation_dt_factor, 0.5);
  ASSERT_TRUE(plan.escalate_below_fraction);
  EXPECT_DOUBLE_EQ(*plan.escalate_below_fraction, 0.7);
  EXPECT_NE(plan.reasons[1].find("below 70 % of its static load"), std::string::npos) << plan.reasons[1];
  EXPECT_NE(plan.reasons[2].find("wheel unloading is asked"), std::string::npos) << plan.reasons[2];
  // Comfort or an irregularity without wheel quantities: the deck and car-body
  // values hold at the run's step, the escalation keeps it.
  for (int kind = 0; kind < 2; ++kind) {
    PlannerInput in = span_15m();
    in.load_model = false;
    in.asks.comfort = kind == 0;
    in.irregularity = kind == 1;
    const EffectsPlan p = plan_effects(in);
    ASSERT_TRUE(p.escalate_below_fraction) << kind;
    EXPECT_DOUBLE_EQ(*p.escalate_below_fraction, 0.5) << kind;
    EXPECT_FALSE(p.escalation_dt_factor) << kind;
  }
  // A load model has no wheels to escalate.
  PlannerInput forces = span_15m();
  forces.asks.wheel_unloading = true;
  EXPECT_FALSE(plan_effects(forces).escalation_dt_factor);
}

TEST(EffectsPlanner, EscalationReasonNamesTheFinerTimeStep) {
  RunSummary s = two_wheels(30000.0);
  s.dt_s = 2.5e-4;
  const auto halved = escalation_reason(s, 0.5, 0.5);
  ASSERT_TRUE(halved);
  EXPECT_NE(halved->find("at dt = 0.000125 s (0.5 x 0.00025 s)"), std::string::npos) << *halved;
  const auto same = escalation_reason(s, 0.5, 1.0);
  ASSERT_TRUE(same);
  EXPECT_EQ(same->find("at dt ="), std::string::npos) << *same;
  EXPECT_EQ(*same, *escalation_reason(s, 0.5));
}

TEST(EffectsPlanner, ModalTimeStepSamplesTheCodeFrequencyWithinTheTolerance) {
  // The largest sample, 1 %: n = ceil(pi / acos(0.99)) = 23 samples per period of 45 Hz: 0.966 ms.
  const double dt = modal_time_step_s(45.0, 0.01, ModalPeaks::kSampled);
  EXPECT_DOUBLE_EQ(dt, 9.66e-4);
  EXPECT_LE(1.0 - std::cos(M_PI * 45.0 * dt), 0.01);
  // A tighter tolerance samples more finely.
  EXPECT_LT(modal_time_step_s(45.0, 0.001, ModalPeaks::kSampled), dt / 3.0);
}

TEST(EffectsPlanner, ModalTimeStepOfRefinedPeaksIsSixteenSamplesAPeriodForOnePercent) {
  // The refined peak of a harmonic alone would allow n = 8 (cos(pi/8) (1 + sin^2(pi/8) / 2) = 0.99153
  // >= 0.99); the recurrence's floor n >= 16 sqrt(0.01 / tolerance) governs: n = 16,
  // dt = 1 / (16 x 45 Hz) = 1.3889 ms, rounded down to 1.38 ms.
  EXPECT_DOUBLE_EQ(modal_time_step_s(45.0, 0.01, ModalPeaks::kRefined), 1.38e-3);
  // 0.1 %: n = ceil(16 sqrt(10)) = 51 (the harmonic alone: 14): 1 / (51 x 45 Hz) = 0.43573 ms.
  EXPECT_DOUBLE_EQ(modal_time_step_s(45.0, 0.001, ModalPeaks::kRefined), 4.35e-4);
  // A tolerance no double-precision step honours stops at 10^6 samples a period, not in an endless search.
  EXPECT_GT(modal_time_step_s(45.0, 1e-300, ModalPeaks::kSampled), 0.0);
}

TEST(EffectsPlanner, ModalTimeStepWithSectionForcesIsTheDecksStep) {
  // The section forces' measured n >= 8 sqrt(0.01 / tolerance) lies below the recurrence's floor
  // 16 sqrt(0.01 / tolerance) that the deck takes too: 1 %, 0.1 % and 5 % (n = ceil(16 sqrt(0.2)) = 8)
  // give the deck's step.
  for (const double tolerance : {0.01, 0.001, 0.05})
    EXPECT_DOUBLE_EQ(modal_time_step_s(45.0, tolerance, ModalPeaks::kRefinedWithSections),
                     modal_time_step_s(45.0, tolerance, ModalPeaks::kRefined))
        << tolerance;
  EXPECT_DOUBLE_EQ(modal_time_step_s(45.0, 0.05, ModalPeaks::kRefined), 2.77e-3);  // 1 / (8 x 45 Hz)
}

TEST(EffectsPlanner, NextRungClimbsTowardFiniteElementsAndUnilateralHertz) {
  // Exact modal moving forces -> moving forces on FE; then the top for a load model.
  const Rung modal_forces;
  const auto fe_forces = next_rung(modal_forces);
  ASSERT_TRUE(fe_forces);
  EXPECT_EQ(fe_forces->name(), "moving_forces/fe");
  EXPECT_EQ(fe_forces->contact_law, "none");
  EXPECT_FALSE(next_rung(*fe_forces));
  // Interaction on the modes keeps its contact law on FE.
  const Rung modal_interaction{"interaction", "modal", "linear-hertz", false};
  const auto fe_interaction = next_rung(modal_interaction);
  ASSERT_TRUE(fe_interaction);
  EXPECT_EQ(fe_interaction->name(), "interaction/fe");
  EXPECT_EQ(fe_interaction->contact_law, "linear-hertz");
  // Linear Hertz (either way) and rigid on FE -> unilateral Hertz, the top.
  for (const Rung& cheaper : {Rung{"interaction", "fe", "linear-hertz", false}, Rung{"interaction", "fe", "linear-hertz", true},
                              Rung{"interaction", "fe", "rigid", false}}) {
    const auto up = next_rung(cheaper);
    ASSERT_TRUE(up) << cheaper.contact_law;
    EXPECT_EQ(up->contact_law, "hertz");
    EXPECT_TRUE(up->unilateral);
    EXPECT_FALSE(next_rung(*up));
  }
}

}  // namespace
}  // namespace railvsi

namespace railvsi {
namespace {

// A multibody train over a structure with track: the partition the hybrid
// structure would make.
// The frequencies are those of the generated deck of three 25 m spans
// (f0 4.2 Hz, f3 36.8 Hz).
PlannerInput interaction_on_track(int track, int interface, int interior) {
  PlannerInput in;
  in.f0_hz = 4.2;
  in.f3_hz = 36.8;
  in.load_model = false;
  in.track_dofs = track;
  in.interface_dofs = interface;
  in.interior_dofs = interior;
  return in;
}

TEST(EffectsPlanner, InteractionOnADeckWithALargeInteriorRunsHybrid) {
  // The generated 3D deck of 20,000 DOFs: 2,124 track DOFs, 540 the track
  // bears on, the rest inside the deck.
  const EffectsPlan plan = plan_effects(interaction_on_track(2124, 540, 17205));
  EXPECT_EQ(plan.rung.name(), "interaction/hybrid");
  EXPECT_DOUBLE_EQ(plan.modal_cutoff_hz, kHybridCutoffFactor * 36.8);
  EXPECT_NE(plan.reasons.back().find("hybrid structure"), std::string::npos);
  EXPECT_TRUE(ignores(plan, "bridge's own modes above 110.4 Hz"));
  EXPECT_FALSE(ignores(plan, "damping coupling"));  // the track keeps its dampers in FE
  // Its next rung up is the same contact law on FE.
  const auto up = next_rung(plan.rung);
  ASSERT_TRUE(up);
  EXPECT_EQ(up->name(), "interaction/fe");
}

TEST(EffectsPlanner, InteractionOnAShortStiffSpanStaysOnFe) {
  // Two 12 m spans of the 3D deck: f3 = 118.6 Hz, the hybrid cut-off would
  // be 356 Hz.
  PlannerInput in = interaction_on_track(628, 90, 2298);
  in.f3_hz = 118.6;
  const EffectsPlan plan = plan_effects(in);
  EXPECT_EQ(plan.rung.name(), "interaction/fe");
  EXPECT_NE(plan.reasons.back().find("355.8 Hz, is above the 250 Hz"), std::string::npos) << plan.reasons.back();
  // 250 Hz is still hybrid: a code frequency of 41.6 Hz.
  in.f3_hz = kHybridMaxCutoffHz / kHybridCutoffFactor;
  EXPECT_EQ(plan_effects(in).rung.structure, "hybrid");
}

TEST(EffectsPlanner, InteractionOnAPlaneViaductStaysOnFe) {
  // The plane viaduct: every deck DOF carries the ballast (no interior).
  const EffectsPlan flat = plan_effects(interaction_on_track(1936, 360, 0));
  EXPECT_EQ(flat.rung.name(), "interaction/fe");
  EXPECT_NE(flat.reasons.back().find("would not make the hybrid structure cheaper"), std::string::npos);
  // An interior, but not four times the interface.
  EXPECT_EQ(plan_effects(interaction_on_track(2000, 600, 2000)).rung.structure, "fe");
  // At the thresholds.
  EXPECT_EQ(plan_effects(interaction_on_track(2000, 250, kHybridMinInteriorDofs)).rung.structure, "hybrid");
  EXPECT_EQ(plan_effects(interaction_on_track(2000, 250, kHybridMinInteriorDofs - 1)).rung.structure, "fe");
}

}  // namespace
}  // namespace railvsi
