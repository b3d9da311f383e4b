#include "study/structure_key.hpp"

#include <cstdint>

#include <fmt/format.h>

#include "core/sha256.hpp"

namespace railvsi::scheduler {
namespace {

void hash_matrix(Sha256& h, const SparseMatrix& A) {
  SparseMatrix c = A;
  c.makeCompressed();
  const std::int64_t dims[3] = {c.rows(), c.cols(), c.nonZeros()};
  h.update(dims, sizeof dims);
  h.update(c.outerIndexPtr(), sizeof(int) * static_cast<std::size_t>(c.outerSize() + 1));
  h.update(c.innerIndexPtr(), sizeof(int) * static_cast<std::size_t>(c.nonZeros()));
  h.update(c.valuePtr(), sizeof(double) * static_cast<std::size_t>(c.nonZeros()));
}

// What a run reads of the structure besides its matrices: rail lines (node
// x and element DOFs) and output points (name, x, DOF).
void hash_rails_and_outputs(Sha256& h, const StructureModel& structure) {
  for (const RailLine& r : structure.rails()) {
    const std::int64_t n[2] = {static_cast<std::int64_t>(r.x_m.size()), static_cast<std::int64_t>(r.element_dofs.size())};
    h.update(n, sizeof n);
    h.update(r.x_m.data(), sizeof(double) * r.x_m.size());
    for (const auto& e : r.element_dofs) h.update(e.data(), sizeof(int) * e.size());
  }
  for (const OutputPoint& o : structure.outputs()) {
    h.update(fmt::format("|{}:{}|{:a}|{}", o.name.size(), o.name, o.x_m, o.dof));
  }
}

}  // namespace

std::string structure_model_hash(const StructureModel& structure) {
  Sha256 h;
  h.update("railvsi structure v1");
  hash_matrix(h, structure.K());
  hash_matrix(h, structure.M());
  hash_matrix(h, structure.C());
  const auto& rail = structure.rail_dofs();
  const std::int64_t n = static_cast<std::int64_t>(rail.size());
  h.update(&n, sizeof n);
  h.update(rail.data(), sizeof(int) * rail.size());
  return h.hex_digest();
}

std::string operator_key(const std::string& structure_hash, const AnalysisOptions& analysis, bool rail_flexibility) {
  // Hex floats: exact, so equal doubles and only equal doubles share a key.
  // A modal operator is another operator: its backend and modes are part of
  // the key (FE keys are unchanged), and so is a static correction turned
  // off (the default's keys are unchanged).
  const std::string modal = analysis.structure_backend == StructureBackend::kModal
                                ? fmt::format("|modal|modes={}|cutoff={:a}{}", analysis.modal_modes,
                                              analysis.modal_cutoff_hz,
                                              analysis.modal_static_correction ? "" : "|no-static-correction")
                            : analysis.structure_backend == StructureBackend::kHybrid
                                ? fmt::format("|hybrid|modes={}|cutoff={:a}", analysis.modal_modes,
                                              analysis.modal_cutoff_hz)
                                : std::string();
  return structure_hash + "/" +
         sha256_hex(fmt::format("railvsi operator v1|{}|dt={:a}|alpha={:a}|beta={:a}|gamma={:a}|flex={}{}",
                                structure_hash, analysis.dt_s, analysis.hht.alpha, analysis.hht.beta,
                                analysis.hht.gamma, rail_flexibility ? 1 : 0, modal));
}

std::string modal_operator_key(const std::string& structure_hash, const StructureModel& structure, double cutoff_hz,
                               double dt_s) {
  Sha256 h;
  h.update(fmt::format("railvsi modal v1|{}|cutoff={:a}|dt={:a}", structure_hash, cutoff_hz, dt_s));
  hash_rails_and_outputs(h, structure);
  return structure_hash + "/" + h.hex_digest();
}

std::string structure_part(const std::string& operator_key) {
  const auto slash = operator_key.find('/');
  return slash == std::string::npos ? operator_key : operator_key.substr(0, slash);
}

std::string hybrid_basis_key(const std::string& structure_part, const StructureModel& structure, int modes,
                             double cutoff_hz) {
  Sha256 h;
  const StructureInfo& info = structure.info();
  h.update(fmt::format("railvsi hybrid basis v1|{}|modes={}|cutoff={:a}|beam={}|bridge={:a},{:a}|f1={:a}",
                       structure_part, modes, cutoff_hz, info.deck_beam ? 1 : 0, info.bridge_start_m,
                       info.bridge_end_m, info.first_frequency_hz));
  hash_rails_and_outputs(h, structure);
  return structure_part + "/" + h.hex_digest();
}

}  // namespace railvsi::scheduler
