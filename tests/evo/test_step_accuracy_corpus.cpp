// The accuracy gate of the time step on the benchmark corpus (tests/bench/corpus/): bodies of the
// paper presets and their champions, built as evolution simulates them, actuated from 0.05 s, stay
// within 1 % RMS of their swing of the converged reference (the same body at dt_fraction 0.2;
// tests/support/step_accuracy.hpp). The engine-only half, on the paper's anchor scenes, is
// tests/engine/test_engine_step_accuracy.cpp.
#include <doctest/doctest.h>

#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "evo/experiment/experiment_io.hpp"
#include "evo/experiment/body_spec_of.hpp"
#include "support/step_accuracy.hpp"

namespace {

struct CorpusBody {
    std::string name;
    bhm::engine::BodySpec spec;
};

// The bodies of one corpus file with between min_voxels and max_voxels voxels once framed, at most
// `count` of them, in file order; actuation from 0.05 s instead of the preset's settling time.
std::vector<CorpusBody> corpus_bodies(const std::string& file, int min_voxels, int max_voxels,
                                      int count) {
    const std::string path = std::string(BHM_SOURCE_DIR) + "/tests/bench/corpus/" + file + ".json";
    std::ifstream in(path);
    REQUIRE(in);
    const nlohmann::json corpus = nlohmann::json::parse(in);
    const std::string preset = corpus.at("experiment").get<std::string>();
    const bhm::evo::Experiment experiment = bhm::evo::load_experiment(
        std::string(BHM_SOURCE_DIR) + "/assets/experiments/" + preset + ".json");
    std::vector<CorpusBody> out;
    for (const auto& entry : corpus.at("bodies")) {
        if (static_cast<int>(out.size()) == count) break;
        const auto body = bhm::evo::apply_frame_and_overrides(
            experiment, bhm::evo::parse_body(entry.at("body"), path));
        bhm::engine::BodySpec spec =
            bhm::evo::make_body_spec(experiment, body, experiment.evolution.seed);
        int voxels = 0;
        for (auto m : spec.material)
            voxels += m != 0;
        if (voxels < min_voxels || voxels > max_voxels) continue;
        spec.actuation.start_s = 0.05;
        out.push_back({file + "/" + entry.at("name").get<std::string>(), spec});
    }
    return out;
}

}  // namespace

TEST_CASE("step accuracy: 20+ corpus bodies follow the converged reference") {
    std::vector<CorpusBody> bodies;
    for (const char* file : {"paper-exp1", "paper-exp1-attached", "paper-exp2"})
        for (CorpusBody& b : corpus_bodies(file, 10, 300, 7))
            bodies.push_back(std::move(b));
    for (const char* file :
         {"paper-exp1-champions", "paper-exp2-champions", "paper-exp1-attached-champions"})
        for (CorpusBody& b : corpus_bodies(file, 10, 450, 2))
            bodies.push_back(std::move(b));
    REQUIRE(bodies.size() >= 20);
    double worst = 0.0;
    for (const CorpusBody& b : bodies) {
        CAPTURE(b.name);
        const bhm::test::TrajectoryError e = bhm::test::step_error(b.spec, 0.2, 40);
        MESSAGE(b.name << ": RMS error " << e.rms_m << " m over a swing of " << e.swing_m << " m ("
                       << 100.0 * e.relative() << " %)");
        CHECK(e.relative() < 0.01);
        worst = std::max(worst, e.relative());
    }
    MESSAGE(bodies.size() << " bodies, largest error " << 100.0 * worst << " % of the swing");
}
