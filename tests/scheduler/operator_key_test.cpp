// The factorization cache key separates operators a job cannot share: a
// modal operator with and without the static correction of its dropped
// modes (the default adds nothing to the key).
#include <gtest/gtest.h>

#include "study/structure_key.hpp"

namespace railvsi::scheduler {
namespace {

TEST(OperatorKey, SeparatesTheModalStaticCorrection) {
  AnalysisOptions a;
  a.structure_backend = StructureBackend::kModal;
  a.modal_cutoff_hz = 60.0;
  const std::string corrected = operator_key("structure", a, true);
  a.modal_static_correction = false;
  EXPECT_NE(operator_key("structure", a, true), corrected);
  // The FE key does not read the modal option.
  AnalysisOptions fe;
  const std::string fe_key = operator_key("structure", fe, true);
  fe.modal_static_correction = false;
  EXPECT_EQ(operator_key("structure", fe, true), fe_key);
}

}  // namespace
}  // namespace railvsi::scheduler
