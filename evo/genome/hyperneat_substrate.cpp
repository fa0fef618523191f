// HyperNEAT's substrate over a lattice (hyperneat_substrate.hpp).
#include "evo/genome/hyperneat_substrate.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include "evo/genome/cppn_decoder.hpp"

namespace bhm::evo {

namespace {

//! Index i of n cells along an axis mapped onto [-1, 1] (cppn_inputs' mapping).
double axis_coordinate(int i, int n) {
    return n > 1 ? -1.0 + 2.0 * i / (n - 1) : 0.0;
}

}  // namespace

HyperNeatSubstrate::HyperNeatSubstrate(std::array<int, 3> size, int outputs,
                                       const HyperNeatSettings& settings)
    : outputs_(outputs), settings_(settings) {
    if (size[0] <= 0 || size[1] <= 0 || size[2] <= 0)
        throw std::invalid_argument("HyperNEAT substrate: the lattice has no cells");
    if (settings.radius < 1)
        throw std::invalid_argument("evolution.hyperneat.radius: must be >= 1");
    if (settings.steps < 1) throw std::invalid_argument("evolution.hyperneat.steps: must be >= 1");
    if (!(settings.weight_threshold >= 0.0))
        throw std::invalid_argument("evolution.hyperneat.weight_threshold: must be >= 0");
    if (outputs < 1) throw std::invalid_argument("HyperNEAT substrate: no output sheet");
    cells_ = static_cast<std::size_t>(size[0]) * size[1] * size[2];
    query_.assign(kHyperNeatInputCount, {});
    const int r = settings.radius;
    auto cell = [&](int x, int y, int z) { return x + size[0] * (y + size[1] * z); };
    for (int bz = 0; bz < size[2]; ++bz)
        for (int by = 0; by < size[1]; ++by)
            for (int bx = 0; bx < size[0]; ++bx)
                for (int dz = -r; dz <= r; ++dz)
                    for (int dy = -r; dy <= r; ++dy)
                        for (int dx = -r; dx <= r; ++dx) {
                            const int ax = bx + dx, ay = by + dy, az = bz + dz;
                            if (ax < 0 || ay < 0 || az < 0 || ax >= size[0] || ay >= size[1] ||
                                az >= size[2])
                                continue;
                            source_.push_back(cell(ax, ay, az));
                            target_.push_back(cell(bx, by, bz));
                            const double pa[3] = {axis_coordinate(ax, size[0]),
                                                  axis_coordinate(ay, size[1]),
                                                  axis_coordinate(az, size[2])};
                            const double pb[3] = {axis_coordinate(bx, size[0]),
                                                  axis_coordinate(by, size[1]),
                                                  axis_coordinate(bz, size[2])};
                            double d2 = 0.0;
                            for (int k = 0; k < 3; ++k) {
                                query_[static_cast<std::size_t>(k)].push_back(pa[k]);
                                query_[static_cast<std::size_t>(3 + k)].push_back(pb[k]);
                                d2 += (pb[k] - pa[k]) * (pb[k] - pa[k]);
                            }
                            query_[6].push_back(std::sqrt(d2));
                            query_[7].push_back(1.0);
                        }
}

SubstrateWeights HyperNeatSubstrate::weights(const Genome& cppn) const {
    if (cppn.input_count != kHyperNeatInputCount || cppn.output_count != cppn_output_count())
        throw std::invalid_argument(
            "HyperNEAT: the CPPN has " + std::to_string(cppn.input_count) + " inputs and " +
            std::to_string(cppn.output_count) + " outputs, the substrate needs " +
            std::to_string(kHyperNeatInputCount) + " and " + std::to_string(cppn_output_count()));
    auto value = cppn_node_values(cppn, query_);
    SubstrateWeights out;
    out.source = source_;
    out.target = target_;
    const double t = settings_.weight_threshold;
    for (int j = 0; j < cppn_output_count(); ++j) {
        std::vector<double> w = std::move(value[static_cast<std::size_t>(cppn.input_count + j)]);
        for (double& v : w)
            if (!(std::fabs(v) >= t)) v = 0.0;  // below the threshold (or NaN): no connection
        out.weights.push_back(std::move(w));
    }
    return out;
}

std::vector<std::vector<double>> HyperNeatSubstrate::activate(const Genome& cppn) const {
    const SubstrateWeights w = weights(cppn);
    const std::size_t pairs = source_.size();
    // I -> H: the input sheet is all ones, so its contribution to H_b is the sum of its weights.
    std::vector<double> drive(cells_, 0.0);
    for (std::size_t p = 0; p < pairs; ++p)
        drive[static_cast<std::size_t>(target_[p])] += w.weights[0][p];
    std::vector<double> h(cells_, 0.0), next(cells_);
    for (int s = 0; s < settings_.steps; ++s) {
        next = drive;
        for (std::size_t p = 0; p < pairs; ++p)
            next[static_cast<std::size_t>(target_[p])] +=
                w.weights[1][p] * h[static_cast<std::size_t>(source_[p])];
        for (std::size_t c = 0; c < cells_; ++c)
            h[c] = std::tanh(next[c]);
    }
    std::vector<std::vector<double>> out(static_cast<std::size_t>(outputs_),
                                         std::vector<double>(cells_, 0.0));
    for (int k = 0; k < outputs_; ++k) {
        const auto& wk = w.weights[static_cast<std::size_t>(kSubstrateHiddenOutputs + k)];
        auto& o = out[static_cast<std::size_t>(k)];
        for (std::size_t p = 0; p < pairs; ++p)
            o[static_cast<std::size_t>(target_[p])] +=
                wk[p] * h[static_cast<std::size_t>(source_[p])];
    }
    return out;
}

}  // namespace bhm::evo
