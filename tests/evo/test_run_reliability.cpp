// What keeps a run directory's work safe: checkpoint checksums and versions, the one-writer lock,
// a damaged run.json repaired with a warning that names it, run.json's rules checked against the
// checkpoint's.
#include <doctest/doctest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "evo/run/checkpoint.hpp"
#include "evo/run/crc32.hpp"
#include "evo/run/evolution_run.hpp"
#include "evo/run/run_directory.hpp"
#include "evo/run/run_lock.hpp"
#include "evo_test_support.hpp"
#include "run_test_support.hpp"
#include "support/scratch.hpp"

using namespace bhm::evo;
namespace fs = std::filesystem;
using bhm::evo::test::run_options;

namespace {

void spit(const fs::path& path, const std::string& text) {
    std::ofstream(path, std::ios::binary) << text;
}

}  // namespace

TEST_CASE("CRC-32 gives the standard check value") {
    CHECK(crc32("123456789") == 0xCBF43926u);
    CHECK(crc32("") == 0u);
    CHECK(crc32("a") == 0xE8B7BE43u);
}

TEST_CASE("a checkpoint whose contents changed but still parse is caught by its checksum") {
    const auto e = test::tiny_experiment();
    const fs::path dir = bhm::test::scratch_dir("rel-crc", false);
    EvolutionRun(e, run_options(2, 2, dir.string())).run();
    const fs::path current = dir / kCheckpointFile;
    std::string text = bhm::test::read_file(current);
    REQUIRE(text.rfind("{\"checksum\":\"crc32:", 0) == 0);
    std::vector<std::string> notes;
    const auto payload = parse_checkpoint_text(text, notes);
    CHECK(notes.empty());
    CHECK(payload.at("format_version") == kCheckpointFormatVersion);
    CHECK(checkpoint_text(payload) == text);  // the format round-trips byte for byte

    // One digit of the generation counter changed: valid JSON, wrong run. Falls back.
    const auto at = text.find("\"generation\": 1");
    REQUIRE(at != std::string::npos);
    text[at + 14] = '0';
    spit(current, text);
    auto resumed = EvolutionRun::resume(run_options(3, 2, dir.string()));
    REQUIRE(resumed->resume_warnings().size() == 1);
    const std::string warning = resumed->resume_warnings()[0];
    CHECK(warning.find(current.string()) == 0);
    CHECK(warning.find("CRC-32") != std::string::npos);
    CHECK(warning.find(kPreviousCheckpointFile) != std::string::npos);
    CHECK(resumed->state().generation == 0);
    CHECK(resumed->checkpoint_path() == (dir / kPreviousCheckpointFile).string());
    resumed.reset();

    // Truncated wrapper, damaged checksum digits, a future version: each named, none used.
    for (const std::string& bad :
         {text.substr(0, text.size() / 2),
          std::string("{\"checksum\":\"crc32:zzzzzzzz\"") + text.substr(28)}) {
        std::vector<std::string> ignored;
        CHECK_THROWS_WITH_AS(parse_checkpoint_text(bad, ignored), doctest::Contains("damaged"),
                             std::runtime_error);
    }
    auto future = payload;
    future["format_version"] = 99;
    CHECK_THROWS_WITH_AS(run_state_from_json(future, "x"),
                         doctest::Contains("unsupported version 99"), std::runtime_error);
    fs::remove_all(dir);
}

TEST_CASE(
    "after a resume from the backup the next checkpoint keeps it, the damaged one set aside") {
    const auto e = test::tiny_experiment();
    const fs::path dir = bhm::test::scratch_dir("rel-keep-backup", false);
    EvolutionRun(e, run_options(2, 2, dir.string()))
        .run();  // generations 0 and 1: both files exist
    const std::string backup = bhm::test::read_file(dir / kPreviousCheckpointFile);
    const std::string damaged = "{\"checksum\":\"crc32:00000000\" damaged";
    spit(dir / kCheckpointFile, damaged);
    auto resumed = EvolutionRun::resume(run_options(2, 2, dir.string()));
    REQUIRE(resumed->state().generation == 0);              // from the backup
    CHECK(resumed->run() == StopReason::GenerationBudget);  // one generation: one checkpoint
    CHECK(resumed->state().generation == 1);
    resumed.reset();
    // The backup slot still holds the good generation-0 checkpoint (it received the damaged file).
    CHECK(bhm::test::read_file(dir / kPreviousCheckpointFile) == backup);
    CHECK(bhm::test::read_file(dir / kDamagedCheckpointFile) == damaged);
    std::vector<std::string> notes;
    CHECK(parse_checkpoint_text(bhm::test::read_file(dir / kCheckpointFile), notes)
              .at("generation") == 1);
    fs::remove_all(dir);
}

TEST_CASE("a format 1 checkpoint (no checksum) is still read, with a warning that names it") {
    const auto e = test::tiny_experiment();
    const fs::path dir = bhm::test::scratch_dir("rel-v1", false);
    EvolutionRun(e, run_options(2, 2, dir.string())).run();
    std::vector<std::string> notes;
    auto payload = parse_checkpoint_text(bhm::test::read_file(dir / kCheckpointFile), notes);
    test::as_positional_cache(payload, 1);  // as format 1 wrote its cache
    spit(dir / kCheckpointFile, payload.dump(1) + "\n");
    auto resumed = EvolutionRun::resume(run_options(3, 2, dir.string()));
    REQUIRE(resumed->resume_warnings().size() == 1);
    CHECK(resumed->resume_warnings()[0].find((dir / kCheckpointFile).string()) == 0);
    CHECK(resumed->resume_warnings()[0].find("not verified") != std::string::npos);
    CHECK(resumed->state().generation == 1);
    fs::remove_all(dir);
}

TEST_CASE(
    "a checkpoint damaged in its first bytes is one line naming it, without the JSON "
    "library's codes") {
    // Issue 41 R9: with no checksum header the file is read as a format 1 checkpoint, and its
    // parse error reached the resume warning as "[json.exception.parse_error.101] ...".
    const auto e = test::tiny_experiment();
    const fs::path dir = bhm::test::scratch_dir("rel-first-bytes", false);
    EvolutionRun(e, run_options(2, 2, dir.string())).run();
    for (const std::string& bad : {std::string(), std::string("{"), std::string("x1 damaged")}) {
        spit(dir / kCheckpointFile, bad);
        auto resumed = EvolutionRun::resume(run_options(3, 2, dir.string()));
        REQUIRE(resumed->resume_warnings().size() == 1);
        const std::string warning = resumed->resume_warnings()[0];
        INFO("'" << bad << "': " << warning);
        CHECK(warning.rfind((dir / kCheckpointFile).string() + ": ", 0) == 0);
        CHECK(warning.find(kPreviousCheckpointFile) != std::string::npos);
        CHECK(warning.find("json.exception") == std::string::npos);
        CHECK(warning.find('\n') == std::string::npos);
        CHECK(resumed->state().generation == 0);
    }
    fs::remove_all(dir);
}

TEST_CASE("a run directory has one writer: a second is refused with the owner's name") {
    const auto e = test::tiny_experiment();
    const fs::path dir = bhm::test::scratch_dir("rel-lock", false);
    {
        EvolutionRun first(e, run_options(2, 2, dir.string()));
        const std::string owner = run_lock_owner(dir.string());
        CHECK(owner.find("pid " + std::to_string(::getpid()) + " on host ") == 0);
        try {
            EvolutionRun second(e, run_options(2, 2, dir.string()));
            FAIL("a second writer was let in");
        } catch (const RunDirectoryBusy& busy) {
            CHECK(std::string(busy.what()).find(owner) != std::string::npos);
        }
        first.run();
        CHECK_THROWS_AS(EvolutionRun::resume(run_options(3, 2, dir.string())), RunDirectoryBusy);
    }
    CHECK_FALSE(fs::exists(dir / kRunLockFile));  // released with the run
    CHECK_NOTHROW(EvolutionRun::resume(run_options(3, 2, dir.string())));
    fs::remove_all(dir);
}

TEST_CASE("a lock left by a killed process is stale and taken over") {
    const fs::path dir = bhm::test::scratch_dir("rel-stale", false);
    fs::create_directories(dir);
    const pid_t child = ::fork();
    REQUIRE(child >= 0);
    if (child == 0) {
        // Take the lock and die without any clean-up, as kill -9 would.
        static_cast<void>(new RunDirectoryLock(dir.string(), "doomed"));
        ::_exit(0);
    }
    int status = 0;
    ::waitpid(child, &status, 0);
    REQUIRE(fs::exists(dir / kRunLockFile));
    CHECK(run_lock_owner(dir.string()).find("doomed") != std::string::npos);
    RunDirectoryLock lock(dir.string(), "heir");
    CHECK(run_lock_owner(dir.string()).find("heir") != std::string::npos);
    fs::remove_all(dir);
}

TEST_CASE("a damaged run.json is named, repaired from the checkpoint, and the run goes on") {
    const auto e = test::tiny_experiment();
    const fs::path dir = bhm::test::scratch_dir("rel-runjson", false);
    EvolutionRun(e, run_options(2, 2, dir.string())).run();
    spit(dir / "run.json", "{\"bhm_version\": \"0.1\", \"seed\": 7, \"experi");
    auto resumed = EvolutionRun::resume(run_options(3, 2, dir.string()));
    REQUIRE(resumed->resume_warnings().size() == 1);
    CHECK(resumed->resume_warnings()[0].find((dir / "run.json").string()) == 0);
    CHECK(resumed->resume_warnings()[0].find("rewritten") != std::string::npos);
    const auto run_json =
        nlohmann::json::parse(bhm::test::read_file(dir / "run.json"));  // really rewritten
    CHECK(run_json.at("experiment").at("name") == "tiny");
    CHECK(resumed->run() == StopReason::GenerationBudget);
    fs::remove_all(dir);
}

TEST_CASE("run.json's rule changes are checked against the checkpoint: a change only run.json "
          "holds is named, not used, and a resume rewrites run.json from the checkpoint") {
    const auto e = test::tiny_experiment();
    const fs::path dir = bhm::test::scratch_dir("rel-runjson-rules", false);
    EvolutionRun(e, run_options(2, 2, dir.string())).run();
    // A clean run: no warning, and the rules in force are the experiment's.
    const RunInfo clean = read_run_info(dir.string());
    CHECK(clean.warnings.empty());
    CHECK(clean.current() == e);

    // Forge a physics change (E x 3) into run.json alone: the checkpoint never saw it.
    auto run_json = nlohmann::json::parse(bhm::test::read_file(dir / "run.json"));
    PhysicsRules stiffer = physics_of(e);
    for (auto& m : stiffer.materials)
        m.youngs_modulus_pa *= 3.0;
    run_json["rule_changes"].push_back(
        {{"generation", 1},
         {"fitness", run_json["experiment"]["fitness"]},
         {"physics", physics_to_json(stiffer, e)}});
    spit(dir / "run.json", run_json.dump(2));

    const RunInfo forged = read_run_info(dir.string());
    REQUIRE(forged.warnings.size() == 1);
    CHECK(forged.warnings[0].find((dir / "run.json").string()) == 0);
    CHECK(forged.warnings[0].find("checkpoint") != std::string::npos);
    CHECK(forged.rule_changes.empty());
    CHECK(forged.current().materials == e.materials);  // not E x 3

    auto resumed = EvolutionRun::resume(run_options(3, 2, dir.string()));
    REQUIRE(resumed->resume_warnings().size() == 1);
    CHECK(resumed->resume_warnings()[0].find("rewritten") != std::string::npos);
    CHECK(read_run_info(dir.string()).warnings.empty());  // run.json agrees again
    CHECK(nlohmann::json::parse(bhm::test::read_file(dir / "run.json"))["rule_changes"].empty());
    CHECK(resumed->run() == StopReason::GenerationBudget);
    resumed.reset();
    fs::remove_all(dir);
}
