#include "evo/search/afpo.hpp"

#include <algorithm>
#include <numeric>
#include <tuple>

namespace bhm::evo {

namespace {

//! The volume as a minimised quantity: voxels when minimised, -voxels when maximised, 0 when off
//! (then it never tells two members apart).
int volume_key(const AfpoObjectives& p, const AfpoOptions& options) {
    switch (options.volume) {
        case VolumeObjective::Minimize:
            return p.voxels;
        case VolumeObjective::Maximize:
            return -p.voxels;
        case VolumeObjective::Off:
            break;
    }
    return 0;
}

}  // namespace

bool dominates(const AfpoObjectives& a, const AfpoObjectives& b, const AfpoOptions& options) {
    const bool active = options.minimize_active, second = options.second_objective;
    const int volume_a = volume_key(a, options), volume_b = volume_key(b, options);
    const bool no_worse = a.fitness >= b.fitness && a.age <= b.age &&
                          (!active || a.active_voxels <= b.active_voxels) &&
                          (!second || a.second >= b.second) && volume_a <= volume_b;
    const bool better = a.fitness > b.fitness || a.age < b.age ||
                        (active && a.active_voxels < b.active_voxels) ||
                        (second && a.second > b.second) || volume_a < volume_b;
    return no_worse && better;
}

bool dominates(const AfpoObjectives& a, const AfpoObjectives& b, bool minimize_active) {
    return dominates(a, b, AfpoOptions{minimize_active, false});
}

std::vector<int> pareto_ranks(const std::vector<AfpoObjectives>& pool, const AfpoOptions& options) {
    // Peel layers: O(n^2) per layer, trivial for AFPO's 2P + 1 = 101.
    const std::size_t n = pool.size();
    std::vector<int> rank(n, -1);
    std::size_t assigned = 0;
    for (int layer = 0; assigned < n; ++layer) {
        std::vector<std::size_t> members;
        for (std::size_t i = 0; i < n; ++i) {
            if (rank[i] >= 0) continue;
            bool dominated = false;
            for (std::size_t j = 0; j < n && !dominated; ++j)
                dominated = j != i && rank[j] < 0 && dominates(pool[j], pool[i], options);
            if (!dominated) members.push_back(i);
        }
        for (auto i : members)
            rank[i] = layer;
        assigned += members.size();
    }
    return rank;
}

std::vector<int> pareto_ranks(const std::vector<AfpoObjectives>& pool, bool minimize_active) {
    return pareto_ranks(pool, AfpoOptions{minimize_active, false});
}

std::vector<int> select_survivors(const std::vector<AfpoObjectives>& pool, int count,
                                  const AfpoOptions& options) {
    const auto rank = pareto_ranks(pool, options);
    std::vector<int> order(pool.size());
    std::iota(order.begin(), order.end(), 0);
    auto key = [&](int i) {
        const auto& p = pool[static_cast<std::size_t>(i)];
        return std::make_tuple(rank[static_cast<std::size_t>(i)], -p.fitness,
                               options.second_objective ? -p.second : 0.0, p.age,
                               options.minimize_active ? p.active_voxels : 0,
                               volume_key(p, options), p.id);
    };
    std::sort(order.begin(), order.end(), [&](int a, int b) { return key(a) < key(b); });
    order.resize(std::min(order.size(), static_cast<std::size_t>(std::max(count, 0))));
    return order;
}

std::vector<int> select_survivors(const std::vector<AfpoObjectives>& pool, int count,
                                  bool minimize_active) {
    return select_survivors(pool, count, AfpoOptions{minimize_active, false});
}

}  // namespace bhm::evo
