#pragma once
// Results by phenotype hash, so survivors, clones and phenotypes met again are not simulated twice.
// Bounded (first in, first out) to keep checkpoints small; eviction order is deterministic, so a
// resumed run hits and misses exactly like an uninterrupted one.
#include <cstddef>
#include <cstdint>
#include <deque>
#include <unordered_map>

#include "evo/evaluate/fitness.hpp"

namespace bhm::evo {

class FitnessCache {
  public:
    explicit FitnessCache(std::size_t capacity = 20000) : capacity_(capacity) {}

    const FitnessReport* find(std::uint64_t hash) const {
        const auto it = reports_.find(hash);
        return it == reports_.end() ? nullptr : &it->second;
    }
    //! Adds a result (ignored when the hash is already present); evicts the oldest beyond capacity.
    void insert(std::uint64_t hash, const FitnessReport& report) {
        if (capacity_ == 0 || !reports_.emplace(hash, report).second) return;
        order_.push_back(hash);
        while (order_.size() > capacity_) {
            reports_.erase(order_.front());
            order_.pop_front();
        }
    }
    void clear() {
        reports_.clear();
        order_.clear();
    }
    std::size_t size() const { return order_.size(); }
    std::size_t capacity() const { return capacity_; }
    //! Hashes oldest first: the order checkpoints store them in.
    const std::deque<std::uint64_t>& insertion_order() const { return order_; }

  private:
    std::size_t capacity_;
    std::unordered_map<std::uint64_t, FitnessReport> reports_;
    std::deque<std::uint64_t> order_;
};

}  // namespace bhm::evo
