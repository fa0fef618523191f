// Replay files: a little-endian binary documented in docs/replay-format.md.
// Encoding goes through explicit byte shuffles so the file is the same on any host.
#include "engine/replay.hpp"

#include <unistd.h>
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <system_error>

#include "engine/io/atomic_file.hpp"
#include "engine/io/text_file.hpp"

namespace bhm::engine {

namespace {

constexpr char kMagic[8] = {'B', 'H', 'M', 'R', 'P', 'L', 'Y', '\0'};
constexpr std::uint32_t kVersion = 1;
// magic, version, nx, ny, nz, voxel_size_m, settle_s, voxel count
constexpr std::uint64_t kHeaderBytes = 8 + 4 + 3 * 4 + 8 + 8 + 4;
constexpr std::uint64_t kPerVoxelBytes = 4 + 1 + 1;  // cell, material, fixed
constexpr std::uint64_t kFrameCountBytes = 4;
constexpr std::uint64_t kFloatsPerVoxelFrame = 3 + 4 + 3;  // position, orientation, size

std::uint64_t frame_bytes(std::uint64_t voxel_count) {
    return 8 + 4 * kFloatsPerVoxelFrame * voxel_count;
}

class Encoder {
  public:
    void bytes(const void* data, std::size_t n) {
        const auto* p = static_cast<const char*>(data);
        out_.append(p, n);
    }
    void u8(std::uint8_t v) { out_.push_back(static_cast<char>(v)); }
    void u32(std::uint32_t v) {
        for (int i = 0; i < 4; ++i)
            out_.push_back(static_cast<char>((v >> (8 * i)) & 0xFFu));
    }
    void u64(std::uint64_t v) {
        for (int i = 0; i < 8; ++i)
            out_.push_back(static_cast<char>((v >> (8 * i)) & 0xFFu));
    }
    void i32(std::int32_t v) { u32(static_cast<std::uint32_t>(v)); }
    void f32(float v) { u32(std::bit_cast<std::uint32_t>(v)); }
    void f64(double v) { u64(std::bit_cast<std::uint64_t>(v)); }
    void f32_array(const std::vector<float>& values) {
        for (float v : values)
            f32(v);
    }
    void reserve(std::size_t n) { out_.reserve(n); }
    const std::string& str() const { return out_; }

  private:
    std::string out_;
};

class Decoder {
  public:
    explicit Decoder(const std::string& data) : data_(data) {}
    std::size_t offset() const { return offset_; }
    std::uint8_t u8() { return static_cast<std::uint8_t>(data_[offset_++]); }
    std::uint32_t u32() {
        std::uint32_t v = 0;
        for (int i = 0; i < 4; ++i)
            v |= static_cast<std::uint32_t>(static_cast<unsigned char>(data_[offset_ + i]))
                 << (8 * i);
        offset_ += 4;
        return v;
    }
    std::uint64_t u64() {
        std::uint64_t v = 0;
        for (int i = 0; i < 8; ++i)
            v |= static_cast<std::uint64_t>(static_cast<unsigned char>(data_[offset_ + i]))
                 << (8 * i);
        offset_ += 8;
        return v;
    }
    std::int32_t i32() { return static_cast<std::int32_t>(u32()); }
    float f32() { return std::bit_cast<float>(u32()); }
    double f64() { return std::bit_cast<double>(u64()); }
    void f32_array(std::vector<float>& out, std::size_t n) {
        out.resize(n);
        for (auto& v : out)
            v = f32();
    }

  private:
    const std::string& data_;
    std::size_t offset_ = 0;
};

[[noreturn]] void fail(const std::string& path, const std::string& what) {
    throw std::runtime_error(path + ": " + what);
}

void check_replay_for_writing(const std::string& path, const Replay& r) {
    const std::size_t n = r.voxel_cell.size();
    if (r.nx <= 0 || r.ny <= 0 || r.nz <= 0)
        fail(path, "cannot write replay: lattice size must be positive");
    if (r.voxel_material.size() != n || r.voxel_fixed.size() != n)
        fail(path,
             "cannot write replay: voxel_cell, voxel_material and voxel_fixed differ in length");
    if (n > std::numeric_limits<std::uint32_t>::max() ||
        r.frames.size() > std::numeric_limits<std::uint32_t>::max())
        fail(path, "cannot write replay: too many voxels or frames");
    for (std::size_t f = 0; f < r.frames.size(); ++f) {
        const VoxelPoses& p = r.frames[f];
        if (p.position_m.size() != 3 * n || p.orientation.size() != 4 * n ||
            p.size_m.size() != 3 * n)
            fail(path, "cannot write replay: frame " + std::to_string(f) + " does not hold " +
                           std::to_string(n) + " voxels");
    }
}

void require_finite(const std::string& path, std::uint64_t frame,
                    const std::vector<std::int32_t>& cells, const std::vector<float>& values,
                    std::size_t per_voxel, const char* what) {
    for (std::size_t i = 0; i < values.size(); ++i) {
        if (std::isfinite(values[i])) continue;
        const std::size_t voxel = i / per_voxel;
        fail(path, "corrupt replay: frame " + std::to_string(frame) + " voxel " +
                       std::to_string(voxel) + " (cell " + std::to_string(cells[voxel]) + ") " +
                       what + " is " + format_number(values[i]) +
                       ", not a finite number; record the replay again");
    }
}

}  // namespace

void write_replay(const std::string& path, const Replay& replay) {
    check_replay_for_writing(path, replay);
    const std::uint64_t n = replay.voxel_cell.size();
    Encoder e;
    e.reserve(kHeaderBytes + kPerVoxelBytes * n + kFrameCountBytes +
              frame_bytes(n) * replay.frames.size());
    e.bytes(kMagic, sizeof kMagic);
    e.u32(kVersion);
    e.i32(replay.nx);
    e.i32(replay.ny);
    e.i32(replay.nz);
    e.f64(replay.voxel_size_m);
    e.f64(replay.settle_s);
    e.u32(static_cast<std::uint32_t>(n));
    for (auto c : replay.voxel_cell)
        e.i32(c);
    for (auto m : replay.voxel_material)
        e.u8(m);
    for (auto f : replay.voxel_fixed)
        e.u8(f);
    e.u32(static_cast<std::uint32_t>(replay.frames.size()));
    for (const VoxelPoses& p : replay.frames) {
        e.f64(p.time_s);
        e.f32_array(p.position_m);
        e.f32_array(p.orientation);
        e.f32_array(p.size_m);
    }
    write_file_atomically(path, e.str());
}

Replay read_replay(const std::string& path) {
    const std::string data = read_text(path, kLargeFileCap);
    const std::uint64_t length = data.size();
    const auto truncated = [&](std::uint64_t expected, const char* where) {
        fail(path, "truncated replay: " + std::string(where) + " needs " +
                       std::to_string(expected) + " bytes, file has " + std::to_string(length));
    };
    if (length < sizeof kMagic && std::memcmp(data.data(), kMagic, length) == 0)
        truncated(kHeaderBytes, "header");
    if (length < sizeof kMagic || std::memcmp(data.data(), kMagic, sizeof kMagic) != 0)
        fail(path, "not a BHM replay file (bad magic)");
    if (length < kHeaderBytes) truncated(kHeaderBytes, "header");

    Decoder d(data);
    for (std::size_t i = 0; i < sizeof kMagic; ++i)
        d.u8();
    const std::uint32_t version = d.u32();
    if (version != kVersion)
        fail(path, "unsupported replay version " + std::to_string(version) + " (this build reads " +
                       std::to_string(kVersion) + ")");
    Replay r;
    r.nx = d.i32();
    r.ny = d.i32();
    r.nz = d.i32();
    r.voxel_size_m = d.f64();
    r.settle_s = d.f64();
    const std::uint64_t n = d.u32();
    if (r.nx <= 0 || r.ny <= 0 || r.nz <= 0)
        fail(path, "corrupt replay: lattice size " + std::to_string(r.nx) + "x" +
                       std::to_string(r.ny) + "x" + std::to_string(r.nz) + " is not positive");
    const std::uint64_t cells = static_cast<std::uint64_t>(r.nx) *
                                static_cast<std::uint64_t>(r.ny) * static_cast<std::uint64_t>(r.nz);
    if (n > cells)
        fail(path, "corrupt replay: " + std::to_string(n) + " voxels do not fit a lattice of " +
                       std::to_string(cells) + " cells");
    if (!(std::isfinite(r.voxel_size_m) && r.voxel_size_m > 0.0))
        fail(path, "corrupt replay: voxel size is not a positive number");
    if (!std::isfinite(r.settle_s) || r.settle_s < 0.0)
        fail(path, "corrupt replay: settle time is not a non-negative number");

    const std::uint64_t voxels_end = kHeaderBytes + kPerVoxelBytes * n;
    if (length < voxels_end + kFrameCountBytes)
        truncated(voxels_end + kFrameCountBytes, "voxel table");
    r.voxel_cell.resize(n);
    r.voxel_material.resize(n);
    r.voxel_fixed.resize(n);
    for (auto& c : r.voxel_cell) {
        c = d.i32();
        if (c < 0 || static_cast<std::uint64_t>(c) >= cells)
            fail(path, "corrupt replay: voxel cell " + std::to_string(c) + " outside the lattice");
    }
    for (auto& m : r.voxel_material)
        m = d.u8();
    for (auto& f : r.voxel_fixed) {
        f = d.u8();
        if (f > 1)
            fail(path, "corrupt replay: voxel fixed flag is " + std::to_string(f) + ", not 0 or 1");
    }

    const std::uint64_t frame_count = d.u32();
    const std::uint64_t expected = voxels_end + kFrameCountBytes + frame_count * frame_bytes(n);
    if (length < expected) truncated(expected, (std::to_string(frame_count) + " frames").c_str());
    if (length > expected)
        fail(path, "corrupt replay: " + std::to_string(length - expected) +
                       " unexpected bytes after the last frame");

    r.frames.resize(frame_count);
    double previous_time = -std::numeric_limits<double>::infinity();
    for (std::uint64_t f = 0; f < frame_count; ++f) {
        VoxelPoses& p = r.frames[f];
        p.time_s = d.f64();
        if (!std::isfinite(p.time_s) || p.time_s < previous_time)
            fail(path, "corrupt replay: frame " + std::to_string(f) +
                           " time is not finite or goes backwards");
        previous_time = p.time_s;
        d.f32_array(p.position_m, 3 * n);
        d.f32_array(p.orientation, 4 * n);
        d.f32_array(p.size_m, 3 * n);
        // Every consumer (colour scales, meshes, VTK, measures) assumes finite poses: refuse
        // inf/NaN here, once, naming where, rather than print "-inf to inf" or write it out.
        require_finite(path, f, r.voxel_cell, p.position_m, 3, "position");
        require_finite(path, f, r.voxel_cell, p.orientation, 4, "orientation");
        require_finite(path, f, r.voxel_cell, p.size_m, 3, "size");
    }
    return r;
}

VoxelPoses pose_at(const Replay& replay, double time_s, PoseSampling sampling) {
    const auto& frames = replay.frames;
    if (frames.empty()) throw std::invalid_argument("replay has no frames");
    // First frame strictly after time_s; the one before it is at or before time_s.
    const auto after = std::upper_bound(frames.begin(), frames.end(), time_s,
                                        [](double t, const VoxelPoses& f) { return t < f.time_s; });
    if (after == frames.begin()) return frames.front();
    const VoxelPoses& a = *(after - 1);
    if (after == frames.end() || sampling == PoseSampling::NearestBefore || a.time_s == time_s)
        return a;
    const VoxelPoses& b = *after;
    if (a.position_m.size() != b.position_m.size() ||
        a.orientation.size() != b.orientation.size() || a.size_m.size() != b.size_m.size())
        throw std::invalid_argument("replay frames differ in voxel count");
    const float f = static_cast<float>((time_s - a.time_s) / (b.time_s - a.time_s));
    VoxelPoses out = a;
    out.time_s = time_s;
    for (std::size_t i = 0; i < out.position_m.size(); ++i)
        out.position_m[i] = a.position_m[i] + f * (b.position_m[i] - a.position_m[i]);
    for (std::size_t i = 0; i < out.size_m.size(); ++i)
        out.size_m[i] = a.size_m[i] + f * (b.size_m[i] - a.size_m[i]);
    for (std::size_t i = 0; i + 3 < out.orientation.size(); i += 4) {
        const float* qa = &a.orientation[i];
        float qb[4] = {b.orientation[i], b.orientation[i + 1], b.orientation[i + 2],
                       b.orientation[i + 3]};
        const float dot = qa[0] * qb[0] + qa[1] * qb[1] + qa[2] * qb[2] + qa[3] * qb[3];
        if (dot < 0.0f)  // q and -q are the same rotation: blend along the shorter arc
            for (float& c : qb)
                c = -c;
        float q[4];
        float norm2 = 0.0f;
        for (int k = 0; k < 4; ++k) {
            q[k] = qa[k] + f * (qb[k] - qa[k]);
            norm2 += q[k] * q[k];
        }
        const float norm = std::sqrt(norm2);
        for (int k = 0; k < 4; ++k)
            out.orientation[i + static_cast<std::size_t>(k)] = norm > 1e-8f ? q[k] / norm : qa[k];
    }
    return out;
}

std::vector<double> voxel_mass_weights(const Replay& replay,
                                       const std::vector<double>& material_density) {
    std::vector<double> mass;
    mass.reserve(replay.voxel_material.size());
    for (const std::uint8_t m : replay.voxel_material)
        mass.push_back(m >= 1 && m <= material_density.size() ? material_density[m - 1] : 1.0);
    return mass;
}

std::array<double, 3> centre_of_mass(const VoxelPoses& poses,
                                     const std::vector<double>& voxel_mass) {
    const std::size_t n = static_cast<std::size_t>(poses.voxel_count());
    const bool weighted = voxel_mass.size() == n;
    std::array<double, 3> sum{0.0, 0.0, 0.0};
    double total = 0.0;
    for (std::size_t v = 0; v < n; ++v) {
        const double w = weighted ? voxel_mass[v] : 1.0;
        for (std::size_t k = 0; k < 3; ++k)
            sum[k] += w * poses.position_m[3 * v + k];
        total += w;
    }
    for (double& s : sum)
        s = total > 0.0 ? s / total : 0.0;
    return sum;
}

}  // namespace bhm::engine
