// read_text, the one reader of whole files: contents byte for byte, and every kind of file that
// must not be read (endless devices, pipes, folders, files over the cap) refused with its name.
#include <doctest/doctest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>

#include "engine/io/text_file.hpp"
#include "support/scratch.hpp"

using namespace bhm::engine;
namespace fs = std::filesystem;

namespace {

fs::path scratch(const std::string& name) {
    return bhm::test::scratch_dir("text-" + name);
}

// The message read_text throws for path, or "" when it reads the file.
std::string refusal(const std::string& path, std::uint64_t cap = kTextFileCap) {
    try {
        read_text(path, cap);
    } catch (const FileReadError& e) {
        CHECK(e.path() == path);
        CHECK(std::string(e.what()) == path + ": " + e.reason());
        return e.what();
    }
    return "";
}

}  // namespace

TEST_CASE("read_text returns the file's bytes, zeros and all") {
    const fs::path file = scratch("bytes") / "a.bin";
    std::string bytes(200000, '\0');
    std::mt19937 rng(7);
    for (char& c : bytes)
        c = static_cast<char>(rng() & 0xff);
    std::ofstream(file, std::ios::binary) << bytes;
    CHECK(read_text(file.string()) == bytes);
    std::ofstream(file, std::ios::binary | std::ios::trunc);
    CHECK(read_text(file.string()).empty());
}

TEST_CASE("read_text refuses endless and non-regular files with their name") {
    const fs::path dir = scratch("special");
    CHECK(refusal("/dev/zero").find("/dev/zero: is not a regular file") == 0);
    CHECK(refusal(dir.string()) == dir.string() + ": is a directory, not a file");
    CHECK(refusal((dir / "none.json").string()) == (dir / "none.json").string() + ": no such file");
    // A FIFO without a writer: opening it must neither block nor be read.
    const fs::path fifo = dir / "pipe";
    REQUIRE(::mkfifo(fifo.c_str(), 0600) == 0);
    CHECK(refusal(fifo.string()).find("is not a regular file") != std::string::npos);
}

TEST_CASE("read_text refuses a file over its cap, naming the cap") {
    const fs::path file = scratch("cap") / "big.json";
    std::ofstream(file, std::ios::binary) << std::string(3 * kMiB + 1, ' ');
    CHECK(refusal(file.string(), 3 * kMiB) ==
          file.string() + ": is larger than the 3 MiB this reader accepts; is it the right file?");
    CHECK(read_text(file.string(), 3 * kMiB + 1).size() == 3 * kMiB + 1);
}

TEST_CASE("format_number is the shortest text that reads back as the same value") {
    CHECK(format_number(0.35) == "0.35");
    CHECK(format_number(5e6) == "5e+06");
    CHECK(format_number(-9.81) == "-9.81");
    CHECK(format_number(0.1f) == "0.1");
    CHECK(format_number(std::numeric_limits<double>::infinity()) == "inf");
    std::mt19937_64 rng(3);
    for (int i = 0; i < 1000; ++i) {
        const double v =
            std::ldexp(static_cast<double>(rng() >> 11), static_cast<int>(rng() % 200) - 150);
        const std::string text = format_number(v);
        double back = 0.0;
        std::from_chars(text.data(), text.data() + text.size(), back);
        CHECK(back == v);
    }
}
