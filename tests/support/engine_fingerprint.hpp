#pragma once
// The engine's anchor scenes, the benchmark corpus as it is simulated, and the hash of a World's
// final state: one definition for bench_engine (which times the scenes and prints their hashes
// with --fingerprint) and tests/engine/test_engine_fingerprints.cpp (which compares the hashes
// of a few of them with stored values, issue 41). Header-only: the benchmark and the engine
// suite are separate executables with no test library between them.
#include <algorithm>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <vector>

#include "engine/body_spec.hpp"
#include "engine/model.hpp"
#include "engine/world.hpp"
#include "evo/experiment/body_spec_of.hpp"
#include "evo/experiment/experiment_io.hpp"

namespace bhm::test {

// Paper Table 1: E = 5 MPa, density 1000, Poisson 0.35, friction 1 / 0.5; CTE 0 passive,
// 0.01 active.
inline engine::Material passive_material() {
    engine::Material m;
    m.cte_per_c = 0.0;
    return m;
}
inline engine::Material active_material() {
    engine::Material m;
    m.cte_per_c = 0.01;
    return m;
}

//! A filled nx x ny x nz block, its x = 0 layer held, material per cell from material_at(x)
//! (1 passive, 2 active), actuated from the first step.
template <class MaterialAt>
engine::BodySpec block_fixed_at_x_min(int nx, int ny, int nz, MaterialAt material_at) {
    engine::BodySpec spec;
    spec.nx = nx;
    spec.ny = ny;
    spec.nz = nz;
    spec.materials = {passive_material(), active_material()};
    spec.material.resize(static_cast<std::size_t>(spec.cell_count()));
    spec.fixed.resize(static_cast<std::size_t>(spec.cell_count()));
    for (int z = 0; z < nz; ++z)
        for (int y = 0; y < ny; ++y)
            for (int x = 0; x < nx; ++x) {
                const auto c = static_cast<std::size_t>(spec.cell_index(x, y, z));
                spec.material[c] = static_cast<std::uint8_t>(material_at(x));
                spec.fixed[c] = x == 0 ? 1 : 0;
            }
    // Actuate from the first step: the benchmark times the actuated steps of an evaluation.
    spec.actuation.start_s = 0.0;
    return spec;
}

//! A named body with its step count at steps scale 1.
struct EngineScene {
    std::string name;
    engine::BodySpec spec;
    std::int64_t steps;  //!< ~3 s of wall time at 1.5e7 voxel-steps/s
};

//! The anchor scenes: solid blocks that between them run every pass of the step (gravity,
//! actuation, floor contact, the Poisson coupling, springs across edges).
inline std::vector<EngineScene> anchor_scenes() {
    using engine::BodySpec;
    std::vector<EngineScene> list;
    // 20x8x7 passive cantilever under gravity, no floor.
    BodySpec cantilever = block_fixed_at_x_min(20, 8, 7, [](int) { return 1; });
    cantilever.environment.floor = false;
    list.push_back({"cantilever_20x8x7", cantilever, 40000});
    // The paper's design space filled with muscle: 8x8x7 all active, 2 Hz, on the floor.
    list.push_back(
        {"active_block_8x8x7", block_fixed_at_x_min(8, 8, 7, [](int) { return 2; }), 100000});
    // 20x8x7 with 4-voxel bands along x: active, passive, active, ...
    list.push_back({"bands_20x8x7",
                    block_fixed_at_x_min(20, 8, 7, [](int x) { return (x / 4) % 2 == 0 ? 2 : 1; }),
                    40000});
    // Two stiffnesses (issue 24): the cantilever with layers z = 1 and 5 of a 10x stiffer
    // passive material, every vertical link between them mixed.
    BodySpec layered = cantilever;
    engine::Material stiff = passive_material();
    stiff.youngs_modulus_pa *= 10.0;
    layered.materials.push_back(stiff);
    for (int z = 0; z < layered.nz; ++z)
        for (int y = 0; y < layered.ny; ++y)
            for (int x = 0; x < layered.nx; ++x)
                if (z == 1 || z == 5) layered.material[layered.cell_index(x, y, z)] = 3;
    list.push_back({"layered_20x8x7", layered, 40000});
    // The worst case of the springs across edges (issue 24): the cantilever as a 10x
    // checkerboard, every stiff voxel joined to its stiff edge neighbours (one spring per voxel
    // and a half).
    BodySpec checkerboard = layered;
    for (int z = 0; z < checkerboard.nz; ++z)
        for (int y = 0; y < checkerboard.ny; ++y)
            for (int x = 0; x < checkerboard.nx; ++x)
                checkerboard.material[checkerboard.cell_index(x, y, z)] = (x + y + z) % 2 ? 3 : 1;
    list.push_back({"checkerboard_20x8x7", checkerboard, 40000});
    return list;
}

//! A scene's steps at bench_engine's --steps-scale (at least one).
inline std::int64_t scene_steps(const EngineScene& scene, double steps_scale) {
    return std::max<std::int64_t>(
        1, static_cast<std::int64_t>(static_cast<double>(scene.steps) * steps_scale));
}

//! A corpus body's steps at bench_engine's --steps-scale: about 2e6 x scale voxel-steps, at
//! least 200 steps.
inline std::int64_t corpus_body_steps(int voxels, double steps_scale) {
    return std::max<std::int64_t>(200, static_cast<std::int64_t>(2e6 * steps_scale / voxels));
}

//! FNV-1a over every voxel's final position and orientation (the doubles' bytes): equal
//! fingerprints before and after an engine change show it kept the results bit for bit.
inline std::uint64_t state_fingerprint(const engine::World& world) {
    std::uint64_t hash = 1469598103934665603ull;
    auto mix = [&](double value) {
        unsigned char bytes[sizeof value];
        std::memcpy(bytes, &value, sizeof value);
        for (unsigned char b : bytes)
            hash = (hash ^ b) * 1099511628211ull;
    };
    for (int v = 0; v < world.model().voxel_count(); ++v) {
        for (double x : world.voxel_position_m(v))
            mix(x);
        for (double q : world.voxel_orientation(v))
            mix(q);
    }
    return hash;
}

//! One body of a corpus file, as evolution simulates it.
struct CorpusBody {
    std::string name;  //!< "<preset>/<name in the file>"
    engine::BodySpec spec;
    int voxels = 0;  //!< filled cells
};

//! A corpus file of tests/bench/corpus (its README) with its preset.
struct Corpus {
    std::string name;  //!< the file's stem: a preset can have several corpora
    evo::Experiment experiment;
    std::vector<CorpusBody> bodies;
};

//! Loads a corpus file and its preset from `assets` (assets/experiments): each body framed as
//! evolution simulates it (a no-op for workspace-sized framed bodies), with phases from the
//! run's seed as evaluate_body draws them. Throws std::runtime_error naming the file.
inline Corpus load_corpus(const std::string& path, const std::string& assets) {
    std::ifstream in(path);
    if (!in) throw std::runtime_error(path + ": cannot open the corpus file");
    nlohmann::json corpus;
    try {
        corpus = nlohmann::json::parse(in);
    } catch (const std::exception& e) {
        throw std::runtime_error(path + ": not valid JSON (" + e.what() + ")");
    }
    const std::string preset = corpus.at("experiment").get<std::string>();
    Corpus out{std::filesystem::path(path).stem().string(),
               evo::load_experiment(assets + "/" + preset + ".json"),
               {}};
    for (const auto& entry : corpus.at("bodies")) {
        const auto body =
            evo::apply_frame_and_overrides(out.experiment, evo::parse_body(entry.at("body"), path));
        CorpusBody b{preset + "/" + entry.at("name").get<std::string>(),
                     evo::make_body_spec(out.experiment, body, out.experiment.evolution.seed)};
        b.voxels = static_cast<int>(std::count_if(b.spec.material.begin(), b.spec.material.end(),
                                                  [](auto m) { return m != 0; }));
        out.bodies.push_back(std::move(b));
    }
    return out;
}

}  // namespace bhm::test
