// The muscle model in experiment files (issue 43): the shipped preset validates and round-trips,
// a muscle slot takes the library's values it leaves out, and bad muscle input is one line
// naming the file and field.
#include <doctest/doctest.h>

#include <string>

#include "evo/experiment/experiment_io.hpp"

using namespace bhm::evo;
using nlohmann::json;

namespace {

const std::string kPreset =
    std::string(BHM_SOURCE_DIR) + "/assets/experiments/muscle-catheter.json";

json preset_json() {
    return experiment_to_json(load_experiment(kPreset));
}

// The problems of an experiment given as JSON, as "file:field: message" lines.
std::vector<std::string> problems_of(const json& j) {
    std::vector<std::string> lines;
    try {
        for (const auto& p : validate_experiment(parse_experiment(j, "e.json"), "e.json"))
            lines.push_back(p.to_string());
    } catch (const ValidationError& e) {
        for (const auto& p : e.problems)
            lines.push_back(p.to_string());
    }
    return lines;
}

bool has(const std::vector<std::string>& lines, const std::string& text) {
    for (const auto& l : lines)
        if (l.find(text) != std::string::npos) return true;
    return false;
}

}  // namespace

TEST_CASE("muscle-catheter.json: a valid muscle experiment that round-trips") {
    const Experiment e = load_experiment(kPreset);
    CHECK(validate_experiment(e, kPreset).empty());
    const auto& m = e.materials[1].physics;
    CHECK(m.actuation_model == bhm::engine::ActuationModel::Muscle);
    CHECK(m.cte_per_c == 0.0);  // the library's strain does not become a cte under the muscle
    CHECK(m.muscle.contraction_strain == 0.1);
    CHECK(m.muscle.frequency_hz == 50.0);  // the slot's, over the library's 2 Hz
    CHECK(e.materials[1].active());
    CHECK_FALSE(e.materials[0].active());
    const json written = experiment_to_json(e);
    CHECK(written["materials"][1]["actuation_model"] == "muscle");
    CHECK(written["materials"][1]["muscle"]["fibre_axis"] == "x");
    CHECK(parse_experiment(written, "again.json") == e);
}

TEST_CASE("bad muscle input is one line naming the field") {
    json j = preset_json();
    j["materials"][1]["muscle"]["rise_s"] = 0.0;
    CHECK(has(problems_of(j), "e.json:materials[1].muscle.rise_s: must be in [0.0001, 100] s"));
    j = preset_json();
    j["materials"][1]["muscle"]["fibre_axis"] = "w";
    CHECK(has(problems_of(j), "e.json:materials[1].muscle.fibre_axis:"));
    j = preset_json();
    j["materials"][1]["muscle"]["rise"] = 0.1;
    CHECK(has(problems_of(j), "e.json:materials[1].muscle.rise: unknown key (did you mean 'rise_s'?)"));
    j = preset_json();
    j["materials"][1]["cte_per_c"] = 0.01;
    CHECK(has(problems_of(j),
              "e.json:materials[1].cte_per_c: must be 0 under the muscle model"));
    j = preset_json();
    j["materials"][1]["muscle"]["stimulus"] = "beating";
    CHECK(has(problems_of(j), "e.json:materials[1].muscle.train_on_s: must be 0 for spontaneous "
                              "beating"));
    // A sine-active material beside the muscle.
    j = preset_json();
    j["materials"].push_back({{"name", "sine"}, {"cte_per_c", 0.01}});
    CHECK(has(problems_of(j), "e.json:materials[1].actuation_model: is muscle but materials[2] is "
                              "active under the sine model"));
}

TEST_CASE("a muscle slot without a sourced contraction strain must give one") {
    json j = preset_json();
    json slot = {{"library", "skeletal-muscle-engineered"},
                 {"poisson_ratio", 0.49},
                 {"actuation_model", "muscle"}};
    j["materials"][1] = slot;
    CHECK(has(problems_of(j), "e.json:materials[1].muscle.contraction_strain: is required: "
                              "library material 'skeletal-muscle-engineered' has no sourced value"));
    slot["muscle"] = {{"contraction_strain", 0.05}};
    j["materials"][1] = slot;
    CHECK(problems_of(j).empty());
    const Experiment e = parse_experiment(j, "e.json");
    CHECK(e.materials[1].physics.muscle.frequency_hz == 2.0);  // the library's
    CHECK(e.materials[1].physics.cte_per_c == 0.0);
}

TEST_CASE("muscle fatigue: off unless given, its fields round-trip and bad values name the field") {
    // Off by default: the preset has no fatigue keys and writes none.
    const Experiment e = load_experiment(kPreset);
    CHECK(e.materials[1].physics.muscle.fatigue_s == 0.0);
    CHECK_FALSE(preset_json()["materials"][1]["muscle"].contains("fatigue_s"));
    // Given: read, written and read back the same.
    json j = preset_json();
    j["materials"][1]["muscle"]["fatigue_s"] = 20.0;
    j["materials"][1]["muscle"]["recovery_s"] = 60.0;
    j["materials"][1]["muscle"]["fatigue_floor"] = 0.3;
    CHECK(problems_of(j).empty());
    const Experiment tired = parse_experiment(j, "e.json");
    const auto& u = tired.materials[1].physics.muscle;
    CHECK(u.fatigue_s == 20.0);
    CHECK(u.recovery_s == 60.0);
    CHECK(u.fatigue_floor == 0.3);
    const json written = experiment_to_json(tired);
    CHECK(written["materials"][1]["muscle"]["fatigue_s"] == 20.0);
    CHECK(parse_experiment(written, "again.json") == tired);
    // Bad values: one line naming the field.
    json bad = j;
    bad["materials"][1]["muscle"]["fatigue_s"] = -1.0;
    CHECK(has(problems_of(bad), "e.json:materials[1].muscle.fatigue_s: must be in [0, 3600]"));
    bad = j;
    bad["materials"][1]["muscle"]["fatigue_floor"] = 1.5;
    CHECK(has(problems_of(bad), "e.json:materials[1].muscle.fatigue_floor: must be in [0, 1]"));
    bad = j;
    bad["materials"][1]["muscle"].erase("recovery_s");
    CHECK(has(problems_of(bad), "e.json:materials[1].muscle.recovery_s: must be > 0 when "
                                "muscle.fatigue_s is"));
    bad = j;
    bad["materials"][1]["muscle"]["fatigue_s"] = 1e-6;
    CHECK(has(problems_of(bad), "e.json:materials[1].muscle.fatigue_s: must be 0 (no fatigue) or "
                                "in [0.0001, 3600] s"));
}
