#include "evo/genome/neat_genes.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace bhm::evo {

namespace {

//! Edge indices sorted by innovation number.
std::vector<std::size_t> by_innovation(const Genome& g) {
    std::vector<std::size_t> order(g.edges.size());
    for (std::size_t i = 0; i < order.size(); ++i)
        order[i] = i;
    std::sort(order.begin(), order.end(), [&](std::size_t x, std::size_t y) {
        return g.edges[x].innovation < g.edges[y].innovation;
    });
    return order;
}

std::int64_t largest_innovation(const Genome& g) {
    std::int64_t m = -1;
    for (const auto& e : g.edges)
        m = std::max(m, e.innovation);
    return m;
}

}  // namespace

GeneAlignment align_genes(const Genome& a, const Genome& b) {
    GeneAlignment out;
    const auto oa = by_innovation(a), ob = by_innovation(b);
    const std::int64_t max_a = largest_innovation(a), max_b = largest_innovation(b);
    std::size_t i = 0, j = 0;
    auto unmatched_a = [&](std::size_t e) {
        (a.edges[e].innovation > max_b ? out.excess_a : out.disjoint_a).push_back(e);
    };
    auto unmatched_b = [&](std::size_t e) {
        (b.edges[e].innovation > max_a ? out.excess_b : out.disjoint_b).push_back(e);
    };
    while (i < oa.size() || j < ob.size()) {
        if (j == ob.size()) {
            unmatched_a(oa[i++]);
        } else if (i == oa.size()) {
            unmatched_b(ob[j++]);
        } else {
            const auto ia = a.edges[oa[i]].innovation, ib = b.edges[ob[j]].innovation;
            if (ia == ib) {
                out.matching.emplace_back(oa[i++], ob[j++]);
            } else if (ia < ib) {
                unmatched_a(oa[i++]);
            } else {
                unmatched_b(ob[j++]);
            }
        }
    }
    return out;
}

double compatibility_distance(const Genome& a, const Genome& b, const NeatSettings& s) {
    const auto al = align_genes(a, b);
    const double excess = static_cast<double>(al.excess_a.size() + al.excess_b.size());
    const double disjoint = static_cast<double>(al.disjoint_a.size() + al.disjoint_b.size());
    double weight_difference = 0.0;
    for (const auto& [x, y] : al.matching)
        weight_difference += std::fabs(a.edges[x].weight - b.edges[y].weight);
    const double w_bar =
        al.matching.empty() ? 0.0 : weight_difference / static_cast<double>(al.matching.size());
    const std::size_t larger = std::max(a.edges.size(), b.edges.size());
    const double n = !s.normalize_by_size || larger < kSmallGenomeGenes
                         ? 1.0
                         : static_cast<double>(larger);
    return s.c1 * excess / n + s.c2 * disjoint / n + s.c3 * w_bar;
}

}  // namespace bhm::evo
