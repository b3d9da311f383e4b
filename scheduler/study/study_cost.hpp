#pragma once
// The CPU time a study will take, predicted before any job runs
// (results/planning/cost_model.hpp): every job's time loop, plus one
// factorization per distinct structure operator (the workers' cache builds
// each once). One scene per train is parsed; the other jobs of the train
// differ only in speed and dt, which change the step count alone.
#include <string>

#include "study/study_plan.hpp"

namespace railvsi::scheduler {

struct StudyCostEstimate {
  double cpu_s = 0.0;
  double setup_cpu_s = 0.0;  // part of cpu_s: the setups (FE factorizations or modal bases)
  std::size_t jobs = 0;
  std::size_t setups = 0;  // distinct operator keys
};

StudyCostEstimate estimate_study_cost(const StudyPlan& plan);
std::string describe(const StudyCostEstimate& estimate);

}  // namespace railvsi::scheduler
