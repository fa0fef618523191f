// The bhm executable's validate command and usage errors, run as a user would run them.
#include <doctest/doctest.h>

#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>

#include "support/scratch.hpp"

namespace {
const std::string kSource = BHM_SOURCE_DIR;
const std::string kBhm = std::string(BHM_BINARY_DIR) + "/bin/bhm";

struct Result {
    int status;
    std::string output;
};

Result run(const std::string& args) {
    const std::string command = kBhm + " " + args + " 2>&1";
    std::FILE* pipe = popen(command.c_str(), "r");
    REQUIRE(pipe != nullptr);
    std::string out;
    char buffer[4096];
    size_t n;
    while ((n = std::fread(buffer, 1, sizeof buffer, pipe)) > 0)
        out.append(buffer, n);
    int raw = pclose(pipe);
    return {WIFEXITED(raw) ? WEXITSTATUS(raw) : 128 + WTERMSIG(raw), out};
}
}  // namespace

TEST_CASE("bhm validate accepts every preset") {
    auto r = run("validate " + kSource + "/assets/experiments/*.json");
    CHECK(r.status == 0);
    // multi-material.json, biohybrid-catheter.json and muscle-catheter.json too
    CHECK(r.output.find("8 file(s) valid") != std::string::npos);
}

TEST_CASE("bhm validate warns outside the validated envelope and still passes") {
    // Muscle (12 kPa) in PDMS (1.8 MPa): a contrast of 150, past the validated 10.
    const auto dir = bhm::test::scratch_dir("validate-envelope");
    const auto path = (dir / "muscle-in-pdms.json").string();
    std::ofstream(path) << R"({"materials": [
        {"name": "pdms", "youngs_modulus_pa": 1.8e6, "poisson_ratio": 0.49},
        {"name": "muscle", "youngs_modulus_pa": 1.2e4, "poisson_ratio": 0.49, "cte_per_c": 0.01}]})";
    auto r = run("validate " + path);
    CHECK(r.status == 0);
    CHECK(r.output.find(path + ":materials: warning: stiffness contrast 150") != std::string::npos);
    CHECK(r.output.find("1 file(s) valid") != std::string::npos);
    std::filesystem::remove_all(dir);
    // Muscle in Ecoflex at nu 0.49 (the catheter preset, contrast 9.9): inside, no warning.
    r = run("validate " + kSource + "/assets/experiments/biohybrid-catheter.json");
    CHECK(r.status == 0);
    CHECK(r.output.find("warning") == std::string::npos);
    // A body of one material: no contrast, no warning.
    r = run("validate " + kSource + "/assets/experiments/quick-demo.json");
    CHECK(r.status == 0);
    CHECK(r.output.find("warning") == std::string::npos);
}

TEST_CASE("bhm materials lists the library with values and sources") {
    auto r = run("materials");
    CHECK(r.status == 0);
    CHECK(r.output.find("ecoflex-00-30  Ecoflex 00-30 (Smooth-On)  (silicone)") != std::string::npos);
    CHECK(r.output.find("Smooth-On, Ecoflex Series Technical Bulletin") != std::string::npos);
    CHECK(r.output.find("cardiomyocyte-tissue") != std::string::npos);
    r = run("materials muscle");
    CHECK(r.status == 0);
    CHECK(r.output.find("skeletal-muscle-engineered") != std::string::npos);
    CHECK(r.output.find("ecoflex") == std::string::npos);
    // A broken library file: one line naming the file and the field, exit 1.
    const auto dir = bhm::test::scratch_dir("materials-cli");
    std::ofstream(dir / "bad.json") << R"({"format_version": 1, "name": "x",
        "category": "silicone", "engine": "e", "youngs_modulus_pa": {"value": 1e5}})";
    r = run("materials --dir " + dir.string());
    CHECK(r.status == 1);
    CHECK(r.output.find((dir / "bad.json").string() + ":youngs_modulus_pa.source: is required") !=
          std::string::npos);
    std::filesystem::remove_all(dir);
}

TEST_CASE(
    "bhm materials and bhm validate name what the library skipped; one damaged file fails "
    "only the experiments naming it") {
    // Issue 41 R10: a FIFO, a folder and a dangling link were skipped without a word, and one
    // damaged file refused every experiment filled from the library.
    const auto dir = bhm::test::scratch_dir("materials-skipped");
    const auto library = dir / "library";
    std::filesystem::create_directories(library / "drafts");
    std::ofstream(library / "good.json") << R"({"format_version": 1, "name": "good rubber",
        "category": "silicone", "engine": "e", "youngs_modulus_pa": {"value": 1e5, "source": "s"},
        "poisson_ratio": {"value": 0.3, "source": "s"}, "density_kg_m3": {"value": 1000,
        "source": "s"}})";
    std::ofstream(library / "bad.json") << R"({"format_version": 1, "name": "x"})";
    REQUIRE(::mkfifo((library / "pipe.json").c_str(), 0644) == 0);
    std::filesystem::create_symlink(library / "nowhere.json", library / "gone.json");
    auto r = run("materials --dir " + library.string());  // a FIFO opened would hang here
    INFO(r.output);
    CHECK(r.status == 1);
    CHECK(r.output.find("good  good rubber  (silicone)") != std::string::npos);
    CHECK(r.output.find((library / "pipe.json").string() + ":(file): skipped: a named pipe") !=
          std::string::npos);
    CHECK(r.output.find((library / "drafts").string() + ":(file): skipped: a folder") !=
          std::string::npos);
    CHECK(r.output.find((library / "gone.json").string() +
                        ":(file): skipped: a symbolic link to a missing file") !=
          std::string::npos);
    CHECK(r.output.find((library / "bad.json").string() + ":category: is required") !=
          std::string::npos);

    ::setenv("BHM_MATERIALS_DIR", library.string().c_str(), 1);
    const auto uses_good = (dir / "uses-good.json").string();
    std::ofstream(uses_good) << R"({"materials": [{"library": "good"},
        {"name": "muscle", "poisson_ratio": 0.3, "cte_per_c": 0.01}]})";
    r = run("validate " + uses_good);
    INFO(r.output);
    CHECK(r.status == 0);
    CHECK(r.output.find("1 file(s) valid") != std::string::npos);
    CHECK(r.output.find("bhm: warning: " + (library / "bad.json").string() + ":") !=
          std::string::npos);
    CHECK(r.output.find("bhm: warning: " + (library / "pipe.json").string() + ":(file): skipped") !=
          std::string::npos);
    const auto uses_bad = (dir / "uses-bad.json").string();
    std::ofstream(uses_bad) << R"({"materials": [{"library": "good"}, {"library": "bad",
        "poisson_ratio": 0.3, "density_kg_m3": 1000, "cte_per_c": 0.01}]})";
    r = run("validate " + uses_bad);
    INFO(r.output);
    CHECK(r.status == 1);
    CHECK(r.output.find(uses_bad +
                        ":materials[1].library: 'bad' cannot be used: its library file "
                        "is damaged (" +
                        (library / "bad.json").string() + ":") != std::string::npos);
    ::unsetenv("BHM_MATERIALS_DIR");
    std::filesystem::remove_all(dir);
}

TEST_CASE("bhm validate reports every problem of a file, one per line") {
    const auto dir = bhm::test::scratch_dir("validate-cli");
    const auto path = (dir / "two-problems.json").string();
    std::ofstream(path) << R"({"materials": [{"name": "p", "poisson_ratio": 0.7},
        {"name": "a", "cte_per_c": 0.01, "youngs_modulus_pa": -1}]})";
    auto r = run("validate " + path);
    CHECK(r.status == 1);
    CHECK(r.output.find(path + ":materials[0].poisson_ratio: must be in [-0.9, 0.49]") !=
          std::string::npos);
    CHECK(r.output.find(path + ":materials[1].youngs_modulus_pa:") != std::string::npos);
    std::filesystem::remove_all(dir);
}

TEST_CASE("a body is checked against the experiment named with it") {
    auto r = run("validate " + kSource + "/assets/experiments/quick-demo.json " + kSource +
                 "/tests/data/bad/body-no-material.json");
    CHECK(r.status == 1);
    CHECK(r.output.find("body-no-material.json:layers[0]: material 7") != std::string::npos);
}

TEST_CASE("usage errors exit 2 with a one-line error and a hint") {
    auto r = run("frobnicate");
    CHECK(r.status == 2);
    CHECK(r.output.rfind("bhm: unknown subcommand 'frobnicate'", 0) == 0);
    r = run("validate --bogus x.json");
    CHECK(r.status == 2);
    CHECK(r.output.rfind("bhm validate: unknown option '--bogus'", 0) == 0);
    r = run("validate");
    CHECK(r.status == 2);
    r = run("--version");
    CHECK(r.status == 0);
    CHECK(r.output.rfind("bhm ", 0) == 0);
    for (const char* sub :
         {"studio", "validate", "materials", "simulate", "evolve", "render", "export"}) {
        CAPTURE(sub);
        r = run(std::string(sub) + " --help");
        CHECK(r.status == 0);
        CHECK(r.output.find("usage: bhm ") != std::string::npos);
    }
}

TEST_CASE("mutated presets through the real binary never crash it") {
    const auto dir = bhm::test::scratch_dir("validate-fuzz");
    const std::string original =
        bhm::test::read_file(kSource + "/assets/experiments/paper-exp3.json");
    std::mt19937 rng(7);
    for (int i = 0; i < 24; ++i) {
        std::string text = original;
        if (i % 2)
            text.resize(rng() % text.size());
        else
            for (int k = 0; k < 4; ++k)
                text[rng() % text.size()] = static_cast<char>(rng() % 256);
        const auto path = (dir / ("m" + std::to_string(i) + ".json")).string();
        std::ofstream(path, std::ios::binary) << text;
        auto r = run("validate --quiet " + path);
        CAPTURE(r.output);
        CHECK((r.status == 0 || r.status == 1));
    }
    auto r = run("validate " + (dir / "does-not-exist.json").string());
    CHECK(r.status == 1);
    CHECK(r.output.find("does-not-exist.json:(file): no such file") != std::string::npos);
    std::filesystem::remove_all(dir);
}

TEST_CASE("bhm validate refuses endless files and folders by name instead of reading them") {
    // Before the capped reader, /dev/zero was read into memory until the machine ran out.
    auto r = run("validate /dev/zero");
    CHECK(r.status == 1);
    CHECK(r.output ==
          "/dev/zero:(file): is not a regular file (a device, pipe or socket); give a "
          "file\n");
    const auto dir = bhm::test::scratch_dir("validate-folder");
    r = run("validate " + dir.string());
    CHECK(r.status == 1);
    CHECK(r.output == dir.string() + ":(file): is a directory, not a file\n");
    // Over the 64 MiB cap of a JSON file: refused before parsing, naming the cap.
    const auto big = dir / "big.json";
    std::ofstream(big).close();
    std::filesystem::resize_file(big, 64 * 1024 * 1024 + 1);  // sparse: no disk used
    r = run("validate " + big.string());
    CHECK(r.status == 1);
    CHECK(r.output.find("big.json:(file): is larger than the 64 MiB") != std::string::npos);
    std::filesystem::remove_all(dir);
}
