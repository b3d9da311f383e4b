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

// Source, sampled range, min, max, mean and RMS of the samples (about zero,
// trapezoidal over x).
nlohmann::ordered_json irregularity_report(const Irregularity& irregularity);

}  // namespace railvsi::cli
