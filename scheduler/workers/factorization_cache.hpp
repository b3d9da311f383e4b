#pragma once
// Structure operators (K_bar factor and rail flexibility) shared by the
// worker threads of one process, keyed by the job's operator key (structure
// hash, dt, HHT parameters, rail flexibility), and what operators for
// several dt share (a modal basis, the hybrid structure's reduction). Least recently used entries
// are dropped to stay within a memory budget; an operator still in use by a
// running job lives on in that job's shared_ptr. Concurrent requests for the
// same key factorize once: the others wait for it.
#include <cstddef>
#include <cstdint>
#include <functional>
#include <list>
#include <map>
#include <memory>
#include <mutex>
#include <condition_variable>
#include <set>
#include <string>

#include "simulation/modal_section_forces.hpp"
#include "solver/hybrid_basis.hpp"
#include "solver/modal_basis.hpp"
#include "solver/structure_operator.hpp"

namespace railvsi::scheduler {

struct CacheStats {
  std::int64_t factorizations = 0;
  std::int64_t hits = 0;
  std::int64_t evictions = 0;
  double factorization_s = 0.0;
};

// What happened between two readings of stats().
CacheStats operator-(const CacheStats& after, const CacheStats& before);

struct CacheLookup {
  std::shared_ptr<const StructureOperator> op;
  bool factorized = false;  // this call built it
  double factorization_s = 0.0;
  int evictions = 0;        // entries dropped to make room for it
};

// The modal rung's counterpart of an operator: the structure's modes up to
// a cut-off and, for a beam deck, its section forces on them; shared by
// every job on that structure (keyed like an operator).
struct ModalModel {
  std::shared_ptr<const ModalBasis> basis;
  std::shared_ptr<const ModalSectionForces> sections;  // null: none
  std::size_t memory_bytes() const;
};

struct BasisLookup {
  std::shared_ptr<const ModalBasis> basis;
  std::shared_ptr<const ModalSectionForces> sections;
  bool built = false;  // this call computed the modes
  double build_s = 0.0;
  int evictions = 0;
};

struct HybridBasisLookup {
  std::shared_ptr<const HybridBasis> basis;
  bool built = false;  // this call computed the reduction
  double build_s = 0.0;
  int evictions = 0;
};

class FactorizationCache {
 public:
  explicit FactorizationCache(std::size_t budget_bytes = std::size_t{2} << 30);

  // The operator of `key`, built by `build` when absent (exceptions of
  // build propagate to this caller; a waiting caller then builds itself).
  CacheLookup get(const std::string& key, const std::function<std::shared_ptr<const StructureOperator>()>& build);
  // The same for a modal basis, sized by ModalModel::memory_bytes(); bases
  // and operators share the budget and the LRU order.
  BasisLookup get_basis(const std::string& key, const std::function<ModalModel()>& build);
  // The same for the hybrid structure's reduction (hybrid_basis_key: one
  // for every dt), sized by HybridBasis::memory_bytes().
  HybridBasisLookup get_hybrid_basis(const std::string& key,
                                     const std::function<std::shared_ptr<const HybridBasis>()>& build);
  CacheStats stats() const;

  // Estimated memory of an operator (StructureOperator::memory_bytes: the
  // CHOLMOD factor or the modes, and the rail flexibility block).
  static std::size_t estimated_bytes(const StructureOperator& op);

 private:
  // One of the three is set.
  struct Model {
    std::shared_ptr<const StructureOperator> op;
    ModalModel modal;
    std::shared_ptr<const HybridBasis> hybrid;
    std::size_t memory_bytes() const;
  };
  struct Entry {
    Model model;
    std::size_t bytes = 0;
    std::list<std::string>::iterator lru;
  };
  struct Lookup {
    Model model;
    bool built = false;
    double build_s = 0.0;
    int evictions = 0;
  };
  Lookup lookup(const std::string& key, const std::function<Model()>& build);
  int evict_to_fit(std::size_t incoming_bytes);  // with mutex_ held

  std::size_t budget_bytes_;
  mutable std::mutex mutex_;
  std::condition_variable built_;
  std::map<std::string, Entry> entries_;
  std::list<std::string> lru_;  // front: most recently used
  std::set<std::string> building_;  // keys being factorized
  std::size_t used_bytes_ = 0;
  CacheStats stats_;
};

}  // namespace railvsi::scheduler
