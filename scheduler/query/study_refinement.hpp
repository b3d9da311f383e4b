#pragma once
// A study with "refine": true grows after each complete pass: the speeds
// study/speed_refinement.hpp chooses around the peaks of each train's
// governing deck acceleration are expanded into jobs like the study's own
// (same document, same trains and profiles, the new speeds) and linked to
// the study after its last job. The job ids are those of the scenes, so a
// refinement repeated (another worker, a second vsi run) adds nothing twice.
#include <cstddef>
#include <string>

#include "store/sqlite.hpp"
#include "study/speed_refinement.hpp"

namespace railvsi::scheduler {

// The jobs linked to the study; 0 when the study does not ask for refinement, when jobs
// of the study are still queued or running, or when its peaks are resolved.
// File names of the study document resolve from the directory of the study
// file as submitted. Throws InputError if the study document no longer
// expands (a file moved).
std::size_t refine_study(Database& db, const std::string& study_id, int max_attempts = 3,
                         const RefineOptions& options = {});

}  // namespace railvsi::scheduler
