#include "evo/genome/neat_innovation.hpp"

namespace bhm::evo {

std::int64_t InnovationTable::connection(std::int64_t from_id, std::int64_t to_id) {
    const auto [it, inserted] = connections_.try_emplace({from_id, to_id}, next_innovation_);
    if (inserted) ++next_innovation_;
    return it->second;
}

InnovationTable::Split InnovationTable::split(std::int64_t innovation, std::int64_t from_id,
                                              std::int64_t to_id) {
    if (const auto it = splits_.find(innovation); it != splits_.end()) return it->second;
    Split s;
    s.node_id = next_node_id_++;
    s.in_innovation = connection(from_id, s.node_id);
    s.out_innovation = connection(s.node_id, to_id);
    splits_.emplace(innovation, s);
    return s;
}

void InnovationTable::new_generation() {
    connections_.clear();
    splits_.clear();
}

}  // namespace bhm::evo
