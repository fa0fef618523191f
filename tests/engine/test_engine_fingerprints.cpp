// Determinism as a test (issue 41; Box2D's test_determinism): the anchor scenes of bench_engine
// and a few bodies of its corpus, stepped as `bench_engine --fingerprint --steps-scale 0.05`
// steps them, must end bit for bit where they ended when the values below were stored. Any
// change to the results of the step changes a hash, so a refactoring or an optimisation that
// claims to keep the physics is checked by ctest rather than by hand. A deliberate change of the
// physics updates the stored values (the failure says how).
// The engine is bit-identical across x86-64 levels (engine/internal/kernel_dispatch.hpp, built
// with -ffp-contract=off), so one value per scene holds for Release, Debug and the portable
// kernel (-DBHM_ENGINE_NO_DISPATCH); all three were checked when the values were stored.
#include <doctest/doctest.h>

#include <cstdint>
#include <cstdio>
#include <map>
#include <string>
#include <vector>

#include "support/engine_fingerprint.hpp"

using namespace bhm;

namespace {

// bench_engine's --steps-scale for these hashes: 2000-5000 steps per anchor scene, at least 200
// per corpus body; under a second in Release for everything here.
constexpr double kStepsScale = 0.05;

struct Stored {
    const char* scene;
    std::uint64_t fingerprint;
};

// The anchor scenes (tests/support/engine_fingerprint.hpp anchor_scenes()).
constexpr Stored kAnchorScenes[] = {
    {"cantilever_20x8x7", 0x82130ad92a9cb62aull},   {"active_block_8x8x7", 0x6308054d80645380ull},
    {"bands_20x8x7", 0xa016c4425a83782bull},        {"layered_20x8x7", 0xc3d0933aac5997d3ull},
    {"checkerboard_20x8x7", 0x16507c23a15e28a2ull},
};

// Corpus bodies (tests/bench/corpus), "<corpus file>:<preset>/<body>": three materials with
// springs across edges, the biohybrid catheter's 2 mm muscle in Ecoflex, a paper preset's random
// body and a paper-exp3 champion inside its passive frame.
// Built from the presets, so they move with the presets' settings: stored again 2026-12-08 when
// the presets took dt_fraction 1.2 and rotary_inertia_scale 1.5 (issue 42; with the old presets
// the old values still held, and the anchor scenes above did not move).
constexpr Stored kCorpusBodies[] = {
    {"multi-material:multi-material/random-14", 0xec47e6927773bb3cull},
    {"biohybrid-catheter:biohybrid-catheter/random-26", 0x9f1b8160d045a867ull},
    {"paper-exp1:paper-exp1/random-02", 0x756c239ac56babf7ull},
    {"paper-exp3-champions:paper-exp3/champion-seed1", 0x49fb6309adc72422ull},
};

std::uint64_t fingerprint_after(const engine::BodySpec& spec, std::int64_t steps,
                                const std::string& scene) {
    engine::World world(engine::Model::build(spec));
    for (std::int64_t i = 0; i < steps; ++i)
        world.step();
    CHECK_MESSAGE(!world.diverged(), scene << " diverged: " << world.divergence_reason());
    return test::state_fingerprint(world);
}

std::string hex(std::uint64_t value) {
    char text[32];
    std::snprintf(text, sizeof text, "0x%016llxull", static_cast<unsigned long long>(value));
    return text;
}

// Compares each scene's hash with its stored value. Every scene runs, so one failure lists all
// that changed, then says what to do and prints the table as it now is (also printed with -s).
void check_fingerprints(const std::string& table, const std::vector<Stored>& stored,
                        const std::map<std::string, std::uint64_t>& measured) {
    bool changed = false;
    std::string now_table = "constexpr Stored " + table + "[] = {\n";
    for (const Stored& s : stored) {
        const std::string scene = s.scene;
        const std::uint64_t now = measured.at(scene);
        changed |= now != s.fingerprint;
        CHECK_MESSAGE(now == s.fingerprint, "engine fingerprint of " << scene << " changed: stored "
                                                                     << hex(s.fingerprint)
                                                                     << ", now " << hex(now));
        now_table += "    {\"" + scene + "\", " + hex(now) + "},\n";
    }
    now_table += "};\n";
    if (changed)
        MESSAGE(
            "The step no longer gives bit-identical results. If the physics changed on "
            "purpose, replace "
            << table
            << " in tests/engine/test_engine_fingerprints.cpp with the table below "
               "(`build/bin/test_engine -tc='engine fingerprints*' -s` prints both tables; "
               "`build/bin/bench_engine --fingerprint --steps-scale 0.05` prints the same hashes) "
               "and say why in the commit message; otherwise find what changed them.\n"
            << now_table);
    else if (doctest::getContextOptions()->success)
        std::printf("%s", now_table.c_str());
}

}  // namespace

TEST_CASE("engine fingerprints: the anchor scenes end bit for bit as stored") {
    std::map<std::string, std::uint64_t> measured;
    for (const test::EngineScene& scene : test::anchor_scenes())
        measured[scene.name] =
            fingerprint_after(scene.spec, test::scene_steps(scene, kStepsScale), scene.name);
    REQUIRE(measured.size() == std::size(kAnchorScenes));
    check_fingerprints("kAnchorScenes", {std::begin(kAnchorScenes), std::end(kAnchorScenes)},
                       measured);
}

TEST_CASE("engine fingerprints: corpus bodies end bit for bit as stored") {
    std::map<std::string, std::uint64_t> measured;
    std::map<std::string, test::Corpus> corpora;  // each file loaded once
    for (const Stored& s : kCorpusBodies) {
        const std::string key = s.scene;
        const std::string file = key.substr(0, key.find(':'));
        const std::string body = key.substr(key.find(':') + 1);
        if (!corpora.contains(file))
            corpora.emplace(
                file, test::load_corpus(BHM_SOURCE_DIR "/tests/bench/corpus/" + file + ".json",
                                        BHM_SOURCE_DIR "/assets/experiments"));
        for (const test::CorpusBody& b : corpora.at(file).bodies)
            if (b.name == body)
                measured[key] =
                    fingerprint_after(b.spec, test::corpus_body_steps(b.voxels, kStepsScale), key);
        REQUIRE_MESSAGE(measured.contains(key), "no body " << body << " in corpus " << file);
    }
    check_fingerprints("kCorpusBodies", {std::begin(kCorpusBodies), std::end(kCorpusBodies)},
                       measured);
}

namespace {

// A muscle body whose controller delays its stimuli (issue 44; engine/internal/muscle_drive.hpp):
// a held 10 x 2 x 2 strip, its bottom layer muscle (10 Hz twitches, nu 0.35, gravity and floor)
// at phases 0.7 c (several delay bins), 3000 steps (0.2 s, two stimulus periods). It runs the
// delayed path, which no scene above takes. Stored from a Release build only.
engine::BodySpec delayed_muscle_strip() {
    engine::Material passive;
    passive.youngs_modulus_pa = 1e6;
    passive.poisson_ratio = 0.35;
    engine::Material muscle = passive;
    muscle.actuation_model = engine::ActuationModel::Muscle;
    muscle.muscle.contraction_strain = 0.1;
    muscle.muscle.frequency_hz = 10.0;
    muscle.muscle.pulse_width_s = 0.01;
    muscle.muscle.rise_s = 0.02;
    muscle.muscle.decay_s = 0.06;
    engine::BodySpec s;
    s.nx = 10;
    s.ny = 2;
    s.nz = 2;
    s.materials = {passive, muscle};
    s.material.assign(40, 1);
    s.fixed.assign(40, 0);
    s.phase_rad.assign(40, 0.0f);
    for (int c = 0; c < 40; ++c) {
        if (c < 20) s.material[c] = 2;
        if (c % 10 == 0) s.fixed[c] = 1;
        s.phase_rad[c] = static_cast<float>(0.7 * c);
    }
    s.actuation.start_s = 0.0;
    return s;
}

constexpr Stored kDelayedMuscle[] = {
    {"delayed_muscle_strip", 0x47a46641d1281201ull},
};

}  // namespace

TEST_CASE("engine fingerprints: a muscle body with delayed stimuli ends bit for bit as stored") {
    const std::map<std::string, std::uint64_t> measured = {
        {"delayed_muscle_strip",
         fingerprint_after(delayed_muscle_strip(), 3000, "delayed_muscle_strip")}};
    check_fingerprints("kDelayedMuscle", {std::begin(kDelayedMuscle), std::end(kDelayedMuscle)},
                       measured);
}
