#pragma once
// The rung a scene runs on, from its "fidelity": the analysis as given (FE),
// a pinned rung, or the effects planner's choice for "auto" (with what the
// scene asks, its irregularity, its train and the structure's frequencies
// and modes).
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "planning/effects_planner.hpp"
#include "simulation/scene.hpp"
#include "planning/deck_frequencies.hpp"

namespace railvsi {

struct ScenePlan {
  Rung rung;
  std::string chosen_by;  // "planner", "pinned", "analysis" (no fidelity key)
  double modal_cutoff_hz = 0.0;
  std::optional<double> escalate_below_fraction;
  std::optional<double> escalation_dt_factor;  // the escalated run's dt / the plan's; absent: 1
  std::vector<std::string> reasons;
  int modes_below_cutoff = -1;  // as the planner counted them ("auto"), else -1
  // A hybrid run on fixed-interface modes whose wheel lost contact is
  // repeated on FE (rung_runner; the free-interface modes, the default,
  // need no repeat); false for the price, which measures the hybrid rung
  // itself.
  bool impact_repeats_on_fe = true;
};

// The analysis options on the plan's structure: interaction on the modes
// (or hybrid: the track in FE, the bridge in its modes) runs the condensed
// direct method on that backend with the plan's cut-off, unless the
// analysis already names its modes.
void apply_rung_structure(const ScenePlan& plan, AnalysisOptions& analysis);

// What a scene asks: its "asks", else what the train can give.
StudyAsks scene_asks(const Scene& scene);
// What a given "asks" list (of a scene or a study) asks.
StudyAsks asks_from_list(const std::vector<std::string>& list);

// The planner's input for a scene on a structure with these frequencies;
// modes_below_cutoff as counted by count_modes (-1: not counted).
PlannerInput planner_input(const Scene& scene, const StudyAsks& asks, const DeckFrequencies& f, int modes_below_cutoff);

// Modes of the structure up to cutoff_hz. Read from lowest_hz (the lowest
// modes already computed, ascending: DeckFrequencies::lowest_hz) when they
// reach past the cut-off; else a Sturm count (one L D L' factor,
// count_modes_below). -1 when they are not read and the structure is larger
// than max_dofs, or K - sigma M cannot be factorized.
int count_modes(const std::shared_ptr<const StructureModel>& structure, double cutoff_hz,
                const std::vector<double>& lowest_hz = {}, int max_dofs = kMaxDofsForDeckFrequencies);

// For "auto" the frequencies are needed (and the modes counted); a pinned
// or as-given scene ignores them.
ScenePlan plan_scene(const Scene& scene, const DeckFrequencies& f);

// The pinned rung object of a job scene for a plan (schemas fidelity_rung).
nlohmann::json pinned_fidelity_json(const EffectsPlan& plan);

}  // namespace railvsi
