#include "evo/genome/body_ops.hpp"

#include <algorithm>
#include <cstring>

namespace bhm::evo {

std::vector<int> face_connected_labels(const Body& body, int* component_count) {
    const int nx = body.size[0], ny = body.size[1], nz = body.size[2];
    const int n = body.cell_count();
    std::vector<int> label(static_cast<std::size_t>(n), -1);
    std::vector<int> stack;
    int next_label = 0;
    for (int start = 0; start < n; ++start) {
        if (body.cells[static_cast<std::size_t>(start)] == 0 ||
            label[static_cast<std::size_t>(start)] >= 0)
            continue;
        label[static_cast<std::size_t>(start)] = next_label;
        stack.assign(1, start);
        while (!stack.empty()) {
            const int cell = stack.back();
            stack.pop_back();
            const int x = cell % nx, y = (cell / nx) % ny, z = cell / (nx * ny);
            auto visit = [&](int neighbour) {
                auto& l = label[static_cast<std::size_t>(neighbour)];
                if (l < 0 && body.cells[static_cast<std::size_t>(neighbour)] != 0) {
                    l = next_label;
                    stack.push_back(neighbour);
                }
            };
            if (x > 0) visit(cell - 1);
            if (x + 1 < nx) visit(cell + 1);
            if (y > 0) visit(cell - nx);
            if (y + 1 < ny) visit(cell + nx);
            if (z > 0) visit(cell - nx * ny);
            if (z + 1 < nz) visit(cell + nx * ny);
        }
        ++next_label;
    }
    if (component_count) *component_count = next_label;
    return label;
}

Body largest_face_connected_component(const Body& body) {
    int components = 0;
    const auto label = face_connected_labels(body, &components);
    if (components <= 1) return body;
    std::vector<int> size(static_cast<std::size_t>(components), 0);
    for (int l : label)
        if (l >= 0) ++size[static_cast<std::size_t>(l)];
    // max_element returns the first maximum: the component met first in index order wins ties.
    const int keep = static_cast<int>(std::max_element(size.begin(), size.end()) - size.begin());
    Body out = body;
    for (std::size_t i = 0; i < out.cells.size(); ++i)
        if (label[i] != keep) {
            out.cells[i] = 0;
            if (i < out.fibre.size()) out.fibre[i] = engine::kMaterialFibreAxis;
            if (i < out.phase.size()) out.phase[i] = 0.0f;
            if (i < out.amplitude.size()) out.amplitude[i] = 1.0f;
        }
    return out;
}

std::uint64_t hash_body(const Body& body) {
    std::uint64_t h = 0xCBF29CE484222325ull;
    auto mix = [&](std::uint8_t byte) {
        h ^= byte;
        h *= 0x100000001B3ull;
    };
    for (int s : body.size)
        for (int b = 0; b < 4; ++b)
            mix(static_cast<std::uint8_t>(static_cast<unsigned>(s) >> (8 * b)));
    for (auto c : body.cells)
        mix(c);
    // Per-voxel fibre axes (only when some cell has its own): a body without them hashes as
    // before, so caches and checkpoints of earlier runs still match.
    if (std::any_of(body.fibre.begin(), body.fibre.end(),
                    [](std::uint8_t a) { return a != engine::kMaterialFibreAxis; })) {
        mix('f');
        for (auto a : body.fibre)
            mix(a);
    }
    // A controller's phase and amplitude per cell (issue 44), only when the body has one.
    if (body.has_controller()) {
        mix('c');
        auto mix_floats = [&](const std::vector<float>& values) {
            for (float v : values) {
                std::uint32_t bits = 0;
                std::memcpy(&bits, &v, sizeof bits);
                for (int b = 0; b < 4; ++b)
                    mix(static_cast<std::uint8_t>(bits >> (8 * b)));
            }
        };
        mix_floats(body.phase);
        mix_floats(body.amplitude);
    }
    return h;
}

int count_filled(const Body& body) {
    return static_cast<int>(
        std::count_if(body.cells.begin(), body.cells.end(), [](std::uint8_t c) { return c != 0; }));
}

int count_active(const Body& body, const std::vector<MaterialEntry>& materials) {
    int active = 0;
    for (auto c : body.cells)
        if (c != 0 && c <= materials.size() && materials[c - 1u].active()) ++active;
    return active;
}

}  // namespace bhm::evo
