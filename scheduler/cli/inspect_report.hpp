#pragma once
// What `vsi inspect` reports about the models of a document, as JSON (the
// text format is rendered from it): what an engineer checks before trusting
// a model.
#include <nlohmann/json.hpp>

#include "model/irregularity.hpp"
#include "model/structure_model.hpp"
#include "model/train.hpp"

namespace railvsi::cli {

// DOFs (deck/track), rail lines, bridge extent and supports, damping used,
// output points.
nlohmann::ordered_json structure_report(const StructureModel& structure);

// The lowest `modes` natural frequencies of the structure alone (no train
// mass) with a mode type each; "status" is "ok" or the failure's name, with
// a "message".
nlohmann::ordered_json modal_report(const StructureModel& structure, int modes);

// Axle count, first-to-last length, each axle's offset and static load
// (multibody: on a rigid level track), vehicle DOFs. Throws InputError if a
// vehicle is not carried by its wheels.
nlohmann::ordered_json train_report(const Train& train);

// The HSLM-A resonance speeds v_i = f0 D / i (i = 1..4) of a train with a
// coach length D (EN 1991-2 Annex E; the passages of coaches D apart in
// phase with every i-th cycle of the fundamental mode f0). Speeds within
// [min_kmh, max_kmh] only; with a study's range, each says whether the
// study runs it. null when the train is no HSLM-A or f0 is unknown.
nlohmann::ordered_json resonance_report(const Train& train, double f0_hz, double min_kmh, double max_kmh);

// Source, sampled range, min, max, mean and RMS of the samples (about zero,
// trapezoidal over x).
nlohmann::ordered_json irregularity_report(const Irregularity& irregularity);

}  // namespace railvsi::cli
