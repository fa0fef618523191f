#include "evo/calibrate/track_wire.hpp"

#include <array>
#include <bit>
#include <cstring>

#include "evo/evaluate/evaluation_wire.hpp"

namespace bhm::evo {

namespace {

constexpr std::array<char, 4> kMagic = {'B', 'H', 'M', 'T'};
enum class Kind : std::uint8_t { Setup = 1, Job = 2, Result = 3 };
constexpr const char* kKindNames[] = {"?", "setup", "job", "result"};

class Writer {
  public:
    explicit Writer(Kind kind) {
        bytes_.append(kMagic.data(), kMagic.size());
        uint(kTrackWireVersion, 2);
        bytes_.push_back(static_cast<char>(kind));
    }
    void uint(std::uint64_t v, int bytes) {
        for (int k = 0; k < bytes; ++k)
            bytes_.push_back(static_cast<char>((v >> (8 * k)) & 0xffu));
    }
    void real(double v) { uint(std::bit_cast<std::uint64_t>(v), 8); }
    void text(const std::string& s) {
        uint(s.size(), 8);
        bytes_ += s;
    }
    std::string take() { return std::move(bytes_); }

  private:
    std::string bytes_;
};

class Reader {
  public:
    Reader(const std::string& bytes, Kind expected) : bytes_(bytes) {
        what_ = std::string("calibration message (") + kKindNames[static_cast<int>(expected)] + ")";
        if (bytes_.size() < kMagic.size() + 3 ||
            std::memcmp(bytes_.data(), kMagic.data(), kMagic.size()) != 0)
            throw WireError(what_ + ": not a BHM calibration message");
        at_ = kMagic.size();
        const auto version = uint(2);
        if (version != kTrackWireVersion)
            throw WireError(what_ + ": wire version " + std::to_string(version) +
                            ", this bhm speaks " + std::to_string(kTrackWireVersion) +
                            " (every rank must run the same bhm build)");
        const auto kind = static_cast<std::uint8_t>(bytes_[at_++]);
        if (kind != static_cast<std::uint8_t>(expected))
            throw WireError(what_ + ": got message kind " + std::to_string(kind));
    }
    std::uint64_t uint(int bytes) {
        need(static_cast<std::size_t>(bytes));
        std::uint64_t v = 0;
        for (int k = 0; k < bytes; ++k)
            v |= static_cast<std::uint64_t>(static_cast<unsigned char>(bytes_[at_++])) << (8 * k);
        return v;
    }
    double real() { return std::bit_cast<double>(uint(8)); }
    std::size_t count(std::size_t each) {
        const std::uint64_t n = uint(8);
        if (each > 0 && n > (bytes_.size() - at_) / each) fail();
        return static_cast<std::size_t>(n);
    }
    std::string text() {
        const std::size_t n = count(1);
        std::string s = bytes_.substr(at_, n);
        at_ += n;
        return s;
    }
    void done() const {
        if (at_ != bytes_.size())
            throw WireError(what_ + ": " + std::to_string(bytes_.size() - at_) +
                            " unexpected trailing bytes");
    }

  private:
    void need(std::size_t n) const {
        if (bytes_.size() - at_ < n) fail();
    }
    [[noreturn]] void fail() const { throw WireError(what_ + ": truncated"); }
    const std::string& bytes_;
    std::size_t at_ = 0;
    std::string what_;
};

void write_positions(Writer& w, const std::vector<std::array<double, 3>>& positions) {
    w.uint(positions.size(), 8);
    for (const auto& p : positions)
        for (double v : p) w.real(v);
}

std::vector<std::array<double, 3>> read_positions(Reader& r) {
    std::vector<std::array<double, 3>> out(r.count(24));
    for (auto& p : out)
        for (double& v : p) v = r.real();
    return out;
}

}  // namespace

std::string encode_track_setup(const TrackSetupMessage& m) {
    Writer w(Kind::Setup);
    w.uint(static_cast<std::uint32_t>(m.requested_threads), 4);
    w.text(m.fit_list);
    w.text(encode_rules({0, m.experiment}));
    for (int k = 0; k < 3; ++k) w.uint(static_cast<std::uint32_t>(m.framed_body.size[k]), 4);
    w.text(std::string(m.framed_body.cells.begin(), m.framed_body.cells.end()));
    w.text(std::string(m.framed_body.fibre.begin(), m.framed_body.fibre.end()));  // "" = none
    const MeasuredTrack& t = m.track;
    w.text(t.source);
    w.uint(t.t_s.size(), 8);
    for (double v : t.t_s) w.real(v);
    w.uint(t.points.size(), 8);
    for (const auto& p : t.points) {
        w.text(p.name);
        w.uint(static_cast<std::uint8_t>(p.kind), 1);
        w.uint(static_cast<std::uint32_t>(p.cell), 4);
        for (bool a : p.axes) w.uint(a ? 1 : 0, 1);
        write_positions(w, p.position_m);
    }
    return w.take();
}

TrackSetupMessage decode_track_setup(const std::string& bytes) {
    Reader r(bytes, Kind::Setup);
    TrackSetupMessage m;
    m.requested_threads = static_cast<std::int32_t>(r.uint(4));
    m.fit_list = r.text();
    m.experiment = decode_rules(r.text()).rules;
    for (int k = 0; k < 3; ++k) m.framed_body.size[k] = static_cast<std::int32_t>(r.uint(4));
    const std::string cells = r.text();
    m.framed_body.cells.assign(cells.begin(), cells.end());
    const std::string fibre = r.text();
    m.framed_body.fibre.assign(fibre.begin(), fibre.end());
    MeasuredTrack& t = m.track;
    t.source = r.text();
    t.t_s.resize(r.count(8));
    for (double& v : t.t_s) v = r.real();
    t.points.resize(r.count(1));
    for (auto& p : t.points) {
        p.name = r.text();
        p.kind = static_cast<TrackPointKind>(r.uint(1));
        p.cell = static_cast<std::int32_t>(r.uint(4));
        for (bool& a : p.axes) a = r.uint(1) != 0;
        p.position_m = read_positions(r);
    }
    r.done();
    return m;
}

std::string encode_track_job(const TrackJobMessage& m) {
    Writer w(Kind::Job);
    w.uint(m.batch, 8);
    w.uint(m.index, 4);
    w.uint(m.x.size(), 8);
    for (double v : m.x) w.real(v);
    return w.take();
}

TrackJobMessage decode_track_job(const std::string& bytes) {
    Reader r(bytes, Kind::Job);
    TrackJobMessage m;
    m.batch = r.uint(8);
    m.index = static_cast<std::uint32_t>(r.uint(4));
    m.x.resize(r.count(8));
    for (double& v : m.x) v = r.real();
    r.done();
    return m;
}

std::string encode_track_result(const TrackResultMessage& m) {
    Writer w(Kind::Result);
    w.uint(m.batch, 8);
    w.uint(m.index, 4);
    w.uint(m.track.diverged ? 1 : 0, 1);
    w.text(m.track.divergence_reason);
    w.real(m.track.wall_s);
    w.uint(m.track.position_m.size(), 8);
    for (const auto& p : m.track.position_m) write_positions(w, p);
    return w.take();
}

TrackResultMessage decode_track_result(const std::string& bytes) {
    Reader r(bytes, Kind::Result);
    TrackResultMessage m;
    m.batch = r.uint(8);
    m.index = static_cast<std::uint32_t>(r.uint(4));
    m.track.diverged = r.uint(1) != 0;
    m.track.divergence_reason = r.text();
    m.track.wall_s = r.real();
    m.track.position_m.resize(r.count(8));
    for (auto& p : m.track.position_m) p = read_positions(r);
    r.done();
    return m;
}

}  // namespace bhm::evo
