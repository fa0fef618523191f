// make_bench_corpus: writes the benchmark corpus of realistic bodies, one JSON file per preset:
// the bodies evolution's generation 0 simulates, i.e. bodies decoded from random CPPN
// genomes (fixed seeds) that pass the preset's constraints, whatever size they come out.
//
//   make_bench_corpus [--assets DIR] [--out DIR] [--count N] [PRESET...]
//
// Defaults: assets/experiments, tests/bench/corpus, 50 bodies, the four paper presets and the two
// of several materials (multi-material, biohybrid-catheter: their bodies have springs across
// voxel edges, whose cost per step the benchmark then shows). The files
// are committed (tests/bench/corpus/README.md); rerun this only to change the corpus. A file:
//   {"experiment": "paper-exp1", "seed": S, "bodies": [{"name": "random-00", "voxels": N,
//    "body": <body JSON as in docs/experiment-format.md>}, ...]}
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <vector>

#include "evo/evaluate/constraints.hpp"
#include "evo/experiment/experiment_io.hpp"
#include "evo/genome/genome.hpp"
#include "evo/genome/phenotype.hpp"
#include "evo/genome/rng.hpp"

using namespace bhm::evo;

namespace {

// One fixed seed per preset, from its name (FNV-1a), independent of the preset's own seed.
std::uint64_t corpus_seed(const std::string& preset) {
    std::uint64_t h = 1469598103934665603ull;
    for (unsigned char c : preset)
        h = (h ^ c) * 1099511628211ull;
    return h;
}

nlohmann::json corpus_of(const std::string& assets, const std::string& preset, int count,
                         std::uint64_t seed) {
    const Experiment e = load_experiment(assets + "/" + preset + ".json");
    const Developer dev(e);
    Rng rng(seed);
    nlohmann::json bodies = nlohmann::json::array();
    int tries = 0;
    while (static_cast<int>(bodies.size()) < count) {
        if (++tries > 1000 * count)
            throw std::runtime_error(preset + ": too few random genomes pass the constraints");
        const Genome g = random_genome(e.evolution.cppn, rng, dev.cppn_output_count());
        const Phenotype ph = dev.develop(g);
        if (!constraint_violation(e.fitness.constraints, e.boundary, dev.space(), ph).empty())
            continue;
        char name[32];
        std::snprintf(name, sizeof name, "random-%02zu", bodies.size());
        bodies.push_back({{"name", name}, {"voxels", ph.voxels}, {"body", body_to_json(ph.body)}});
    }
    return {{"experiment", preset}, {"seed", seed}, {"bodies", bodies}};
}

}  // namespace

int main(int argc, char** argv) {
    try {
        std::string assets = "assets/experiments", out = "tests/bench/corpus";
        int count = 50;
        std::vector<std::string> presets;
        for (int i = 1; i < argc; ++i) {
            const std::string a = argv[i];
            auto value = [&]() -> std::string {
                if (i + 1 >= argc) throw std::runtime_error(a + " needs a value");
                return argv[++i];
            };
            if (a == "--assets")
                assets = value();
            else if (a == "--out")
                out = value();
            else if (a == "--count")
                count = std::stoi(value());
            else
                presets.push_back(a);
        }
        if (presets.empty())
            presets = {"paper-exp1", "paper-exp1-attached", "paper-exp2",
                       "paper-exp3", "multi-material",      "biohybrid-catheter"};
        std::filesystem::create_directories(out);
        for (std::size_t k = 0; k < presets.size(); ++k) {
            const auto corpus = corpus_of(assets, presets[k], count, corpus_seed(presets[k]));
            const std::string path = out + "/" + presets[k] + ".json";
            write_file_atomically(path, corpus.dump(1) + "\n");
            std::cerr << path << ": " << corpus["bodies"].size() << " bodies\n";
        }
    } catch (const std::exception& e) {
        std::cerr << "make_bench_corpus: " << e.what() << "\n";
        return 1;
    }
    return 0;
}
