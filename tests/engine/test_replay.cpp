// Replay files: bit-exact round trip, and each kind of damage reported with the right reason.
#include <doctest/doctest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <stdexcept>
#include <string>

#include "engine/replay.hpp"
#include "support/scratch.hpp"

namespace fs = std::filesystem;
using bhm::engine::Replay;
using bhm::engine::VoxelPoses;

namespace {

fs::path fresh_dir(const std::string& name) {
    return bhm::test::output_dir("replay", name);
}

// Three voxels of a 2x2x1 lattice, two frames, with values chosen to exercise float bits
// (negative zero, denormal, extremes) so the round trip has to be bit-exact, not approximately
// equal.
Replay sample_replay() {
    Replay r;
    r.nx = 2;
    r.ny = 2;
    r.nz = 1;
    r.voxel_size_m = 0.01;
    r.settle_s = 1.0;
    r.voxel_cell = {0, 1, 3};
    r.voxel_material = {1, 2, 1};
    r.voxel_fixed = {1, 0, 0};
    for (int f = 0; f < 2; ++f) {
        VoxelPoses p;
        p.time_s = f / 30.0;
        for (int v = 0; v < 3; ++v) {
            p.position_m.insert(p.position_m.end(),
                                {0.005f + 0.01f * v, -0.0f + 1e-7f * f, 0.005f * (1 + f)});
            p.orientation.insert(p.orientation.end(), {1.0f, 0.0f, 1e-40f * f, -0.0f});
            p.size_m.insert(p.size_m.end(), {0.01f, std::numeric_limits<float>::max(), 0.0101f});
        }
        r.frames.push_back(p);
    }
    return r;
}

bool same_bits(const std::vector<float>& a, const std::vector<float>& b) {
    if (a.size() != b.size()) return false;
    for (std::size_t i = 0; i < a.size(); ++i)
        if (std::bit_cast<std::uint32_t>(a[i]) != std::bit_cast<std::uint32_t>(b[i])) return false;
    return true;
}

std::string read_bytes(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void write_bytes(const fs::path& path, const std::string& bytes) {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

std::string error_of(const fs::path& path) {
    try {
        bhm::engine::read_replay(path.string());
    } catch (const std::runtime_error& e) {
        return e.what();
    }
    return "";
}

}  // namespace

TEST_CASE("replay round trip is bit-exact") {
    const fs::path file = fresh_dir("roundtrip") / "r.bin";
    const Replay in = sample_replay();
    bhm::engine::write_replay(file.string(), in);
    const Replay out = bhm::engine::read_replay(file.string());

    CHECK(out.nx == 2);
    CHECK(out.ny == 2);
    CHECK(out.nz == 1);
    CHECK(std::bit_cast<std::uint64_t>(out.voxel_size_m) == std::bit_cast<std::uint64_t>(0.01));
    CHECK(out.settle_s == 1.0);
    CHECK(out.voxel_cell == in.voxel_cell);
    CHECK(out.voxel_material == in.voxel_material);
    CHECK(out.voxel_fixed == in.voxel_fixed);
    REQUIRE(out.frames.size() == 2);
    for (int f = 0; f < 2; ++f) {
        CHECK(std::bit_cast<std::uint64_t>(out.frames[f].time_s) ==
              std::bit_cast<std::uint64_t>(in.frames[f].time_s));
        CHECK(same_bits(out.frames[f].position_m, in.frames[f].position_m));
        CHECK(same_bits(out.frames[f].orientation, in.frames[f].orientation));
        CHECK(same_bits(out.frames[f].size_m, in.frames[f].size_m));
        CHECK(out.frames[f].voxel_count() == 3);
    }
    // Writing what was read gives the same bytes: nothing is lost or reordered.
    const fs::path again = file.parent_path() / "again.bin";
    bhm::engine::write_replay(again.string(), out);
    CHECK(read_bytes(again) == read_bytes(file));
}

TEST_CASE("replay file size and layout match docs/replay-format.md") {
    const fs::path file = fresh_dir("layout") / "r.bin";
    bhm::engine::write_replay(file.string(), sample_replay());
    const std::string bytes = read_bytes(file);
    // header 44 + 3 voxels x 6 + frame count 4 + 2 frames x (8 + 3 x 10 x 4)
    CHECK(bytes.size() == 44 + 18 + 4 + 2 * (8 + 120));
    CHECK(std::memcmp(bytes.data(), "BHMRPLY\0", 8) == 0);
    CHECK(static_cast<unsigned char>(bytes[8]) == 1);  // version 1, little-endian u32
    CHECK(bytes[9] == 0);
    // nx = 2 little-endian at offset 12
    CHECK(static_cast<unsigned char>(bytes[12]) == 2);
    // voxel count at offset 40, then cell of voxel 2 (= 3) at 44 + 8
    CHECK(static_cast<unsigned char>(bytes[40]) == 3);
    CHECK(static_cast<unsigned char>(bytes[52]) == 3);
    // frame count after the voxel table
    CHECK(static_cast<unsigned char>(bytes[44 + 18]) == 2);
}

TEST_CASE("an empty replay (no voxels, no frames) round-trips") {
    const fs::path file = fresh_dir("empty") / "r.bin";
    Replay in;
    in.nx = in.ny = in.nz = 1;
    bhm::engine::write_replay(file.string(), in);
    const Replay out = bhm::engine::read_replay(file.string());
    CHECK(out.voxel_cell.empty());
    CHECK(out.frames.empty());
}

TEST_CASE("truncated replay names the file and says truncated") {
    const fs::path dir = fresh_dir("truncated");
    const fs::path good = dir / "good.bin";
    bhm::engine::write_replay(good.string(), sample_replay());
    const std::string bytes = read_bytes(good);

    // Cut inside the last frame, inside the voxel table, inside the header, inside the magic.
    for (std::size_t keep : {bytes.size() - 1, std::size_t{50}, std::size_t{20}, std::size_t{3}}) {
        CAPTURE(keep);
        const fs::path cut = dir / ("cut" + std::to_string(keep) + ".bin");
        write_bytes(cut, bytes.substr(0, keep));
        const std::string message = error_of(cut);
        CHECK(message.find(cut.string()) != std::string::npos);
        CHECK(message.find("truncated") != std::string::npos);
    }
}

TEST_CASE("wrong magic, wrong version, trailing garbage and a missing file are each named") {
    const fs::path dir = fresh_dir("damaged");
    const fs::path good = dir / "good.bin";
    bhm::engine::write_replay(good.string(), sample_replay());
    const std::string bytes = read_bytes(good);

    SUBCASE("wrong magic") {
        std::string bad = bytes;
        bad[0] = 'X';
        write_bytes(dir / "magic.bin", bad);
        const std::string message = error_of(dir / "magic.bin");
        CHECK(message.find((dir / "magic.bin").string()) != std::string::npos);
        CHECK(message.find("bad magic") != std::string::npos);
    }
    SUBCASE("a text file") {
        write_bytes(dir / "text.bin", "{\"size\": [1, 1, 1]}\n");
        CHECK(error_of(dir / "text.bin").find("bad magic") != std::string::npos);
    }
    SUBCASE("future version") {
        std::string bad = bytes;
        bad[8] = 7;
        write_bytes(dir / "version.bin", bad);
        CHECK(error_of(dir / "version.bin").find("unsupported replay version 7") !=
              std::string::npos);
    }
    SUBCASE("trailing garbage") {
        write_bytes(dir / "long.bin", bytes + "xyz");
        CHECK(error_of(dir / "long.bin").find("3 unexpected bytes") != std::string::npos);
    }
    SUBCASE("voxel cell outside the lattice") {
        std::string bad = bytes;
        bad[44] = 9;  // voxel 0's cell; the lattice has 4 cells
        write_bytes(dir / "cell.bin", bad);
        CHECK(error_of(dir / "cell.bin").find("outside the lattice") != std::string::npos);
    }
    SUBCASE("missing file") {
        const std::string message = error_of(dir / "nope.bin");
        CHECK(message.find("nope.bin") != std::string::npos);
        CHECK(message.find("no such file") != std::string::npos);
    }
}

TEST_CASE("writing is atomic: a failed write leaves the old file intact") {
    const fs::path dir = fresh_dir("atomic");
    const fs::path file = dir / "r.bin";
    bhm::engine::write_replay(file.string(), sample_replay());
    const std::string before = read_bytes(file);

    Replay inconsistent = sample_replay();
    inconsistent.frames[1].position_m.pop_back();
    CHECK_THROWS_WITH_AS(bhm::engine::write_replay(file.string(), inconsistent),
                         doctest::Contains("frame 1 does not hold 3 voxels"), std::runtime_error);
    CHECK(read_bytes(file) == before);

    // No temporary files are left behind.
    int entries = 0;
    for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir))
        ++entries;
    CHECK(entries == 1);
}

TEST_CASE("writing into a missing directory fails with the path") {
    const fs::path file = fresh_dir("nodir") / "missing" / "r.bin";
    CHECK_THROWS_WITH_AS(bhm::engine::write_replay(file.string(), sample_replay()),
                         doctest::Contains(file.string().c_str()), std::runtime_error);
}

TEST_CASE("non-finite poses are refused at the reader, naming the frame and the voxel") {
    const fs::path dir = fresh_dir("non-finite");
    const float inf = std::numeric_limits<float>::infinity();
    const float nan = std::numeric_limits<float>::quiet_NaN();
    SUBCASE("a position") {
        Replay r = sample_replay();
        r.frames[1].position_m[3 * 2 + 1] = nan;  // frame 1, voxel 2 (cell 3), y
        bhm::engine::write_replay((dir / "p.bin").string(), r);
        CHECK(error_of(dir / "p.bin") ==
              (dir / "p.bin").string() +
                  ": corrupt replay: frame 1 voxel 2 (cell 3) position is nan, not a finite "
                  "number; record the replay again");
    }
    SUBCASE("a size") {
        Replay r = sample_replay();
        r.frames[0].size_m[3 * 1] = -inf;
        bhm::engine::write_replay((dir / "s.bin").string(), r);
        CHECK(error_of(dir / "s.bin").find("frame 0 voxel 1 (cell 1) size is -inf") !=
              std::string::npos);
    }
    SUBCASE("an orientation") {
        Replay r = sample_replay();
        r.frames[1].orientation[4 * 0 + 3] = inf;
        bhm::engine::write_replay((dir / "q.bin").string(), r);
        CHECK(error_of(dir / "q.bin").find("frame 1 voxel 0 (cell 0) orientation is inf") !=
              std::string::npos);
    }
}
