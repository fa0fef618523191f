#include "evo/genome/cppn_decoder.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

namespace bhm::evo {

CppnMaterials cppn_materials(const Experiment& experiment) {
    CppnMaterials m;
    if (experiment.evolution.cppn.material_outputs == MaterialOutputs::PerMaterial)
        for (std::size_t i = 0; i < experiment.materials.size() && i < 255; ++i)
            m.palette.push_back(static_cast<std::uint8_t>(i + 1));
    for (std::size_t i = 0; i < experiment.materials.size() && i < 255; ++i) {
        const auto index = static_cast<std::uint8_t>(i + 1);
        if (experiment.materials[i].active()) {
            if (m.active == 0) m.active = index;
        } else if (experiment.materials[i].physics.cte_per_c == 0.0 && m.passive == 0) {
            m.passive = index;
        }
    }
    return m;
}

CppnFibres cppn_fibres(const Experiment& experiment) {
    CppnFibres f;
    if (!experiment.evolution.cppn.fibre_outputs) return f;
    const std::size_t n = std::min<std::size_t>(experiment.materials.size(), 255);
    f.muscle.assign(n + 1, 0);
    for (std::size_t i = 0; i < n; ++i) {
        const engine::Material& m = experiment.materials[i].physics;
        f.muscle[i + 1] =
            m.actuation_model == engine::ActuationModel::Muscle && engine::is_active(m);
    }
    return f;
}

namespace {

//! Index i of n cells along an axis mapped onto [-1, 1].
double axis_coordinate(int i, int n) {
    return n > 1 ? -1.0 + 2.0 * i / (n - 1) : 0.0;
}

}  // namespace

std::array<std::vector<double>, kInputCount> cppn_inputs(std::array<int, 3> size) {
    std::array<std::vector<double>, kInputCount> inputs;
    const std::size_t cells = static_cast<std::size_t>(size[0]) * size[1] * size[2];
    for (auto& v : inputs)
        v.resize(cells);
    double largest_norm = 0.0;
    std::size_t c = 0;
    for (int z = 0; z < size[2]; ++z)
        for (int y = 0; y < size[1]; ++y)
            for (int x = 0; x < size[0]; ++x, ++c) {
                const double px = axis_coordinate(x, size[0]);
                const double py = axis_coordinate(y, size[1]);
                const double pz = axis_coordinate(z, size[2]);
                inputs[kInputX][c] = px;
                inputs[kInputY][c] = py;
                inputs[kInputZ][c] = pz;
                inputs[kInputD][c] = std::sqrt(px * px + py * py + pz * pz);
                inputs[kInputBias][c] = 1.0;
                largest_norm = std::max(largest_norm, inputs[kInputD][c]);
            }
    for (auto& d : inputs[kInputD])
        d = largest_norm > 0.0 ? -1.0 + 2.0 * d / largest_norm : 0.0;
    return inputs;
}

std::vector<std::vector<double>> cppn_node_values(const Genome& genome,
                                                  std::span<const std::vector<double>> inputs) {
    if (static_cast<int>(inputs.size()) != genome.input_count)
        throw std::invalid_argument("CPPN genome has " + std::to_string(genome.input_count) +
                                    " inputs, the query " + std::to_string(inputs.size()));
    const std::size_t cells = inputs.empty() ? 0 : inputs[0].size();
    const auto order = topological_order(genome);
    // Incoming edges grouped per target node, kept in genome order so sums are reproducible.
    std::vector<std::vector<const CppnEdge*>> incoming(
        static_cast<std::size_t>(genome.node_count()));
    for (const auto& e : genome.edges)
        incoming[static_cast<std::size_t>(e.to)].push_back(&e);

    std::vector<std::vector<double>> value(static_cast<std::size_t>(genome.node_count()));
    for (int i = 0; i < genome.input_count; ++i)
        value[static_cast<std::size_t>(i)] = inputs[static_cast<std::size_t>(i)];
    for (int node : order) {
        if (genome.is_input(node)) continue;
        auto& out = value[static_cast<std::size_t>(node)];
        out.assign(cells, 0.0);
        for (const CppnEdge* e : incoming[static_cast<std::size_t>(node)]) {
            const auto& in = value[static_cast<std::size_t>(e->from)];
            const double w = e->weight;
            for (std::size_t c = 0; c < cells; ++c)
                out[c] += w * in[c];
        }
        if (genome.is_hidden(node)) {
            const Activation f =
                genome.hidden[static_cast<std::size_t>(node - genome.first_hidden())];
            for (auto& v : out)
                v = activate(f, v);
        }
    }
    return value;
}

CppnDecoder::CppnDecoder(std::array<int, 3> size, CppnMaterials materials, CppnFibres fibres)
    : size_(size), materials_(std::move(materials)), fibres_(std::move(fibres)) {
    if (size[0] <= 0 || size[1] <= 0 || size[2] <= 0)
        throw std::invalid_argument("CPPN design space must have at least one cell per axis");
    inputs_ = cppn_inputs(size);
}

Body CppnDecoder::decode(const Genome& genome) const {
    if (genome.output_count != output_count())
        throw std::invalid_argument("genome has " + std::to_string(genome.output_count) +
                                    " outputs, the experiment's CPPN " +
                                    std::to_string(output_count()) +
                                    " (evolution.cppn.material_outputs, fibre_outputs)");
    return paint_values(cppn_node_values(genome, inputs_));
}

Body CppnDecoder::paint(const std::vector<std::vector<double>>& outputs) const {
    if (static_cast<int>(outputs.size()) != output_count())
        throw std::invalid_argument("substrate gives " + std::to_string(outputs.size()) +
                                    " outputs, the experiment's lattice needs " +
                                    std::to_string(output_count()));
    // The node layout paint_values reads: outputs after kInputCount (unused) input slots.
    std::vector<std::vector<double>> value(kInputCount);
    value.insert(value.end(), outputs.begin(), outputs.end());
    return paint_values(value);
}

Body CppnDecoder::paint_values(const std::vector<std::vector<double>>& value) const {
    const std::size_t cells = inputs_[0].size();
    Body body;
    body.size = size_;
    body.cells.assign(cells, 0);
    paint_materials(value, body);
    if (fibres_.enabled()) {
        body.fibre.assign(cells, engine::kMaterialFibreAxis);
        const std::size_t first = static_cast<std::size_t>(kInputCount) +
                                  static_cast<std::size_t>(materials_.output_count());
        for (std::size_t c = 0; c < cells; ++c) {
            const std::uint8_t m = body.cells[c];
            if (m == 0 || m >= fibres_.muscle.size() || !fibres_.muscle[m]) continue;
            std::uint8_t best = 0;
            for (std::uint8_t axis = 1; axis < 3; ++axis)
                if (value[first + axis][c] > value[first + best][c]) best = axis;
            body.fibre[c] = best;
        }
    }
    return body;
}

void CppnDecoder::paint_materials(const std::vector<std::vector<double>>& value, Body& body) const {
    const std::size_t cells = body.cells.size();
    if (!materials_.palette.empty()) {
        const auto& present = value[kInputCount];
        for (std::size_t c = 0; c < cells; ++c) {
            if (!(present[c] > 0.0)) continue;
            std::size_t best = 0;
            for (std::size_t k = 1; k < materials_.palette.size(); ++k)
                if (value[kInputCount + 1 + k][c] > value[kInputCount + 1 + best][c]) best = k;
            body.cells[c] = materials_.palette[best];
        }
        return;
    }
    const auto& present = value[kOutputMaterial];
    const auto& active = value[kOutputActive];
    for (std::size_t c = 0; c < cells; ++c) {
        if (!(present[c] > 0.0)) continue;
        const std::uint8_t m = active[c] > 0.0 ? materials_.active : materials_.passive;
        if (m == 0)
            throw std::invalid_argument(
                active[c] > 0.0
                    ? "experiment has no active material (cte > 0) for the CPPN's active output"
                    : "experiment has no passive material (cte == 0) for the CPPN's passive "
                      "output");
        body.cells[c] = m;
    }
}

}  // namespace bhm::evo
