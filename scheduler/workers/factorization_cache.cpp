#include "workers/factorization_cache.hpp"

#include <chrono>


namespace railvsi::scheduler {

CacheStats operator-(const CacheStats& after, const CacheStats& before) {
  return {after.factorizations - before.factorizations, after.hits - before.hits,
          after.evictions - before.evictions, after.factorization_s - before.factorization_s};
}

FactorizationCache::FactorizationCache(std::size_t budget_bytes) : budget_bytes_(budget_bytes) {}

std::size_t FactorizationCache::estimated_bytes(const StructureOperator& op) { return op.memory_bytes(); }

int FactorizationCache::evict_to_fit(std::size_t incoming_bytes) {
  int evicted = 0;
  while (!lru_.empty() && used_bytes_ + incoming_bytes > budget_bytes_) {
    const auto it = entries_.find(lru_.back());
    used_bytes_ -= it->second.bytes;
    entries_.erase(it);
    lru_.pop_back();
    ++evicted;
  }
  stats_.evictions += evicted;
  return evicted;
}

CacheLookup FactorizationCache::get(const std::string& key,
                                    const std::function<std::shared_ptr<const StructureOperator>()>& build) {
  const Lookup l = lookup(key, [&] { return Model{build(), ModalModel{}, nullptr}; });
  return {l.model.op, l.built, l.build_s, l.evictions};
}

std::size_t ModalModel::memory_bytes() const {
  return (basis ? basis->memory_bytes() : 0) + (sections ? sections->memory_bytes() : 0);
}

BasisLookup FactorizationCache::get_basis(const std::string& key, const std::function<ModalModel()>& build) {
  const Lookup l = lookup(key, [&] { return Model{nullptr, build(), nullptr}; });
  return {l.model.modal.basis, l.model.modal.sections, l.built, l.build_s, l.evictions};
}

HybridBasisLookup FactorizationCache::get_hybrid_basis(const std::string& key,
                                                       const std::function<std::shared_ptr<const HybridBasis>()>& build) {
  const Lookup l = lookup(key, [&] { return Model{nullptr, ModalModel{}, build()}; });
  return {l.model.hybrid, l.built, l.build_s, l.evictions};
}

std::size_t FactorizationCache::Model::memory_bytes() const {
  if (op) return estimated_bytes(*op);
  if (hybrid) return hybrid->memory_bytes();
  return modal.memory_bytes();
}

FactorizationCache::Lookup FactorizationCache::lookup(const std::string& key, const std::function<Model()>& build) {
  std::unique_lock lock(mutex_);
  for (;;) {
    if (const auto it = entries_.find(key); it != entries_.end()) {
      lru_.splice(lru_.begin(), lru_, it->second.lru);
      ++stats_.hits;
      return {it->second.model, false, 0.0, 0};
    }
    if (!building_.count(key)) break;
    built_.wait(lock);  // another thread builds this key
  }
  building_.insert(key);
  lock.unlock();
  Lookup result;
  const auto start = std::chrono::steady_clock::now();
  try {
    result.model = build();
  } catch (...) {
    lock.lock();
    building_.erase(key);
    built_.notify_all();
    throw;
  }
  result.built = true;
  result.build_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const std::size_t bytes = result.model.memory_bytes();
  lock.lock();
  building_.erase(key);
  ++stats_.factorizations;
  stats_.factorization_s += result.build_s;
  // A model larger than the whole budget is used but not kept, and evicts
  // nothing (checked before evicting: it would have emptied the cache).
  if (bytes <= budget_bytes_) {
    result.evictions = evict_to_fit(bytes);
    lru_.push_front(key);
    entries_[key] = Entry{result.model, bytes, lru_.begin()};
    used_bytes_ += bytes;
  }
  built_.notify_all();
  return result;
}

CacheStats FactorizationCache::stats() const {
  std::lock_guard lock(mutex_);
  return stats_;
}

}  // namespace railvsi::scheduler
