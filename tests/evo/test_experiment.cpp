// Experiment and body files: presets validate, round trips are exact, every broken file in
// tests/data/bad names the field at fault, and no mutated input crashes the loader.
#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>

#include "evo/experiment/body_spec_of.hpp"
#include "evo/experiment/experiment_io.hpp"
#include "support/scratch.hpp"

namespace fs = std::filesystem;
using namespace bhm::evo;

namespace {
const std::string kSource = BHM_SOURCE_DIR;
const std::vector<std::string> kPresets = {"paper-exp1", "paper-exp1-attached", "paper-exp2",
                                           "paper-exp3", "quick-demo"};
std::string preset_path(const std::string& name) {
    return kSource + "/assets/experiments/" + name + ".json";
}
}  // namespace

TEST_CASE("every preset validates and matches the paper's settings") {
    for (const auto& name : kPresets) {
        CAPTURE(name);
        Experiment e = load_experiment(preset_path(name));
        CHECK(validate_experiment(e, name).empty());
        CHECK(e.materials.size() == 2);
        CHECK(e.materials[1].physics.cte_per_c == doctest::Approx(0.01));
        CHECK(e.materials[0].physics.youngs_modulus_pa == doctest::Approx(5e6));
        CHECK(e.actuation.frequency_hz == doctest::Approx(2.0));
        CHECK(e.boundary.faces[0] == BoundaryKind::Fixed);
        CHECK(e.boundary.faces[1] == BoundaryKind::Free);
        CHECK(!e.description.empty());
    }
    auto exp3 = load_experiment(preset_path("paper-exp3"));
    CHECK(exp3.workspace_size == std::array<int, 3>{20, 8, 7});
    CHECK(exp3.fitness.measure == FitnessMeasure::ComFinalYz);
    auto exp1 = load_experiment(preset_path("paper-exp1"));
    CHECK(exp1.simulation.settle_s == 1.0);
    CHECK(exp1.simulation.evaluate_s == 10.0);
    CHECK_FALSE(exp1.fitness.constraints.attached_to_fixed_face);
    CHECK(load_experiment(preset_path("paper-exp1-attached"))
              .fitness.constraints.attached_to_fixed_face);
}

TEST_CASE("experiment round trip: load, save, load is identical") {
    const fs::path dir = bhm::test::scratch_dir("roundtrip");
    for (const auto& name : kPresets) {
        CAPTURE(name);
        Experiment a = load_experiment(preset_path(name));
        const std::string out = (dir / (name + ".json")).string();
        save_experiment(out, a);
        Experiment b = load_experiment(out);
        CHECK(a == b);
        save_experiment(out, b);
        CHECK(experiment_to_json(a) == experiment_to_json(load_experiment(out)));
    }
    fs::remove_all(dir);
}

TEST_CASE("actuation.phase_offset_rad: round trip, range, and every voxel's phase moved by it") {
    const fs::path dir = bhm::test::scratch_dir("phase-offset");
    Experiment a = load_experiment(preset_path("quick-demo"));
    // Absent in the presets: 0, and not written, so files without one stay as they were.
    CHECK(a.actuation.phase_offset_rad == 0.0);
    CHECK_FALSE(experiment_to_json(a)["actuation"].contains("phase_offset_rad"));
    a.actuation.phase_offset_rad = -1.25;
    const std::string out = (dir / "offset.json").string();
    save_experiment(out, a);
    CHECK(experiment_to_json(a)["actuation"]["phase_offset_rad"] == -1.25);
    const Experiment b = load_experiment(out);
    CHECK(b.actuation.phase_offset_rad == -1.25);
    CHECK(a == b);
    // Outside [-pi, pi]: refused, naming the field.
    auto j = experiment_to_json(a);
    j["actuation"]["phase_offset_rad"] = 3.5;
    try {
        (void)parse_experiment(j, "x.json");
        FAIL("a phase offset of 3.5 rad was accepted");
    } catch (const ValidationError& e) {
        REQUIRE(e.problems.size() == 1);
        CHECK(e.problems[0].field == "actuation.phase_offset_rad");
    }
    // The engine's phases: uniform ones all equal to the offset; random ones each moved by it.
    Body body;
    body.size = a.workspace_size;
    body.cells.assign(static_cast<std::size_t>(body.cell_count()), 2);
    const Body framed = apply_frame_and_overrides(a, body);
    for (float phase : make_body_spec(b, framed, 7).phase_rad) CHECK(phase == doctest::Approx(-1.25));
    Experiment r0 = b, r1 = b;
    r0.actuation.phase = r1.actuation.phase = PhaseMode::Random;
    r0.actuation.phase_offset_rad = 0.0;
    const auto p0 = make_body_spec(r0, framed, 7).phase_rad, p1 = make_body_spec(r1, framed, 7).phase_rad;
    REQUIRE(p0.size() == p1.size());
    for (std::size_t k = 0; k < p0.size(); ++k) CHECK(p1[k] - p0[k] == doctest::Approx(-1.25));
    fs::remove_all(dir);
}

TEST_CASE("missing keys take the documented defaults") {
    auto e = parse_experiment(nlohmann::json::parse(R"({"materials": [
        {"name": "p", "cte_per_c": 0}, {"name": "a", "cte_per_c": 0.01}]})"),
                              "mem");
    CHECK(e.workspace_size == std::array<int, 3>{8, 8, 7});
    CHECK(e.voxel_size_m == 0.01);
    CHECK(e.simulation.dt_fraction == 0.9);
    CHECK(e.simulation.bond_damping_ratio == 1.0);
    CHECK(e.actuation.temperature_amplitude_c == doctest::Approx(14.47));
    CHECK(e.environment.gravity_m_s2 == doctest::Approx(-9.81));
    CHECK(e.evolution.population == 50);
    CHECK(e.evolution.max_neutral_retries == 1500);
}

TEST_CASE("unknown keys get a did-you-mean suggestion") {
    try {
        parse_experiment(nlohmann::json::parse(R"({"materials": [{"name": "p"}, {"name": "a",
            "cte_per_c": 0.01}], "simulation": {"settle": 1}})"),
                         "mem.json");
        FAIL("expected a ValidationError");
    } catch (const ValidationError& e) {
        REQUIRE(e.problems.size() == 1);
        CHECK(e.problems[0].field == "simulation.settle");
        CHECK(e.problems[0].message.find("did you mean 'settle_s'") != std::string::npos);
        CHECK(e.problems[0].to_string().rfind("mem.json:simulation.settle: ", 0) == 0);
    }
}

TEST_CASE("every broken file in tests/data/bad fails and names the field") {
    const auto demo = load_experiment(preset_path("quick-demo"));
    std::ifstream list(kSource + "/tests/data/bad/expected.txt");
    std::string line;
    int cases = 0;
    while (std::getline(list, line)) {
        if (line.empty() || line[0] == '#') continue;
        std::istringstream fields(line);
        std::string file, field;
        fields >> file >> field;
        const std::string path = kSource + "/tests/data/bad/" + file;
        CAPTURE(file);
        std::vector<Problem> problems;
        const bool is_body = bhm::test::read_file(path).find("\"layers\"") != std::string::npos;
        try {
            if (is_body) {
                auto body = load_body(path);
                problems = validate_body_against(body, demo, path);
            } else {
                load_experiment(path);
            }
        } catch (const ValidationError& e) {
            problems = e.problems;
        }
        REQUIRE_FALSE(problems.empty());
        bool named = false;
        for (const auto& p : problems) {
            CHECK(p.file == path);
            named = named || p.field == field;
        }
        INFO("first problem: " << problems.front().to_string());
        CHECK(named);
        ++cases;
    }
    CHECK(cases >= 20);
}

TEST_CASE("body round trip and framing") {
    Body body;
    body.size = {3, 2, 2};
    body.cells = {1, 2, 0, 1, 1, 1, 0, 0, 2, 2, 1, 0};
    auto j = body_to_json(body);
    CHECK(j["layers"][0] == "120111");
    CHECK(parse_body(j, "mem") == body);

    auto exp3 = load_experiment(preset_path("paper-exp3"));
    Body inner;
    inner.size = {18, 6, 5};
    inner.cells.assign(18 * 6 * 5, 2);
    auto framed = apply_frame_and_overrides(exp3, inner);
    CHECK(framed.size == std::array<int, 3>{20, 8, 7});
    CHECK(framed.cells[framed.index(0, 0, 0)] == 1);   // frame corner
    CHECK(framed.cells[framed.index(19, 4, 3)] == 1);  // x+ frame
    CHECK(framed.cells[framed.index(1, 1, 1)] == 2);   // design space starts inside the frame
    CHECK(framed.cells[framed.index(18, 6, 5)] == 2);
    int frame = 0;
    for (auto c : framed.cells)
        frame += c == 1;
    CHECK(frame == 20 * 8 * 7 - 18 * 6 * 5);

    auto spec = make_body_spec(exp3, framed, 0);
    int fixed = 0;
    for (auto f : spec.fixed)
        fixed += f;
    CHECK(fixed == 8 * 7);  // the whole x- layer
    CHECK(spec.actuation.start_s == 1.0);
}

TEST_CASE("mutated presets never crash the loader") {
    std::mt19937 rng(12345);
    int rejected = 0, accepted = 0;
    for (const auto& name : kPresets) {
        const std::string original = bhm::test::read_file(preset_path(name));
        for (int i = 0; i < 80; ++i) {
            std::string text = original;
            switch (i % 4) {
                case 0:
                    text.resize(rng() % text.size());
                    break;  // truncated
                case 1:
                    for (int k = 0; k < 3; ++k)
                        text[rng() % text.size()] = static_cast<char>(rng() % 256);
                    break;
                case 2: {  // a number replaced by a string, an array, null or a huge value
                    static const char* replacements[] = {"\"x\"", "[]", "null", "1e400",
                                                         "-7",    "{}", "true"};
                    auto pos = text.find_first_of("0123456789", rng() % text.size());
                    if (pos != std::string::npos)
                        text = text.substr(0, pos) + replacements[rng() % 7] + text.substr(pos + 1);
                    break;
                }
                default: {  // a key renamed
                    auto pos = text.find('"', rng() % text.size());
                    if (pos != std::string::npos && pos + 1 < text.size())
                        text.insert(pos + 1, "z");
                }
            }
            try {
                auto json = nlohmann::json::parse(text, nullptr, false);
                if (json.is_discarded()) {
                    ++rejected;
                    continue;
                }
                parse_experiment(json, "fuzz.json");
                ++accepted;
            } catch (const ValidationError& e) {
                CHECK_FALSE(e.problems.empty());
                ++rejected;
            }
        }
    }
    CHECK(rejected + accepted == 400);
    CHECK(rejected > 300);
}
