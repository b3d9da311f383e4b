#pragma once
// One run of the direct method (DESIGN.md "The direct method, condensed").
// The Simulation holds only const things; run() creates the per-run state.
#include <memory>

#include "simulation/result.hpp"
#include "simulation/scene.hpp"
#include "solver/structure_operator.hpp"

namespace railvsi {

// Build the structure operator a scene needs (K_bar factor and rail
// flexibility for its dt and HHT parameters). Shareable between runs with
// the same key. Throws InputError if the structure cannot be factorized.
std::shared_ptr<const StructureOperator> make_structure_operator(const Scene& scene);

class Simulation {
 public:
  // `op` may be null: it is then built for this scene. The scene is copied
  // (it holds only shared immutable models and options).
  explicit Simulation(Scene scene, std::shared_ptr<const StructureOperator> op = nullptr);
  // Never throws for numerical trouble: the status of the Result tells.
  Result run() const;

 private:
  Scene scene_;
  std::shared_ptr<const StructureOperator> op_;
};

}  // namespace railvsi
