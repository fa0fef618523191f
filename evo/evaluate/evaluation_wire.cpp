#include "evo/evaluate/evaluation_wire.hpp"

#include <array>
#include <cstring>

#include <nlohmann/json.hpp>

#include "evo/evaluate/fitness_json.hpp"
#include "evo/experiment/experiment_io.hpp"
#include "evo/experiment/json_reader.hpp"

namespace bhm::evo {

namespace {

constexpr std::array<char, 4> kMagic = {'B', 'H', 'M', 'W'};
enum class Kind : std::uint8_t { Rules = 1, Job = 2, Result = 3 };
constexpr const char* kKindNames[] = {"?", "rules", "job", "result"};

class Writer {
  public:
    explicit Writer(Kind kind) {
        bytes_.append(kMagic.data(), kMagic.size());
        u16(kEvaluationWireVersion);
        bytes_.push_back(static_cast<char>(kind));
    }
    void u16(std::uint16_t v) { little_endian(v, 2); }
    void u32(std::uint32_t v) { little_endian(v, 4); }
    void u64(std::uint64_t v) { little_endian(v, 8); }
    void i32(std::int32_t v) { u32(static_cast<std::uint32_t>(v)); }
    void raw(const void* data, std::size_t size) {
        bytes_.append(static_cast<const char*>(data), size);
    }
    std::string take() { return std::move(bytes_); }

  private:
    void little_endian(std::uint64_t v, int bytes) {
        for (int k = 0; k < bytes; ++k)
            bytes_.push_back(static_cast<char>((v >> (8 * k)) & 0xffu));
    }
    std::string bytes_;
};

class Reader {
  public:
    Reader(const std::string& bytes, Kind expected) : bytes_(bytes) {
        const std::string what =
            std::string("evaluation message (") + kKindNames[static_cast<int>(expected)] + ")";
        if (bytes_.size() < kMagic.size() + 3 ||
            std::memcmp(bytes_.data(), kMagic.data(), kMagic.size()) != 0)
            throw WireError(what + ": not a BHM evaluation message");
        at_ = kMagic.size();
        const auto version = u16();
        if (version != kEvaluationWireVersion)
            throw WireError(what + ": wire version " + std::to_string(version) +
                            ", this bhm speaks " + std::to_string(kEvaluationWireVersion) +
                            " (every rank must run the same bhm build)");
        const auto kind = static_cast<std::uint8_t>(bytes_[at_++]);
        if (kind != static_cast<std::uint8_t>(expected))
            throw WireError(what + ": got message kind " + std::to_string(kind));
        what_ = what;
    }
    std::uint16_t u16() { return static_cast<std::uint16_t>(little_endian(2)); }
    std::uint32_t u32() { return static_cast<std::uint32_t>(little_endian(4)); }
    std::uint64_t u64() { return little_endian(8); }
    std::int32_t i32() { return static_cast<std::int32_t>(u32()); }
    std::string rest() {
        std::string s = bytes_.substr(at_);
        at_ = bytes_.size();
        return s;
    }
    void raw(void* out, std::size_t size) {
        need(size);
        std::memcpy(out, bytes_.data() + at_, size);
        at_ += size;
    }
    void done() const {
        if (at_ != bytes_.size())
            throw WireError(what_ + ": " + std::to_string(bytes_.size() - at_) +
                            " unexpected trailing bytes");
    }
    const std::string& what() const { return what_; }

  private:
    void need(std::size_t size) const {
        if (bytes_.size() - at_ < size) throw WireError(what_ + ": truncated");
    }
    std::uint64_t little_endian(int bytes) {
        need(static_cast<std::size_t>(bytes));
        std::uint64_t v = 0;
        for (int k = 0; k < bytes; ++k)
            v |= static_cast<std::uint64_t>(static_cast<unsigned char>(bytes_[at_++])) << (8 * k);
        return v;
    }
    const std::string& bytes_;
    std::size_t at_ = 0;
    std::string what_ = "evaluation message";
};

nlohmann::json parse_json(Reader& in) {
    try {
        return nlohmann::json::parse(in.rest());
    } catch (const nlohmann::json::exception& e) {
        throw WireError(in.what() + ": bad JSON: " + without_json_tags(e.what()));
    }
}

Experiment rules_from_json(const nlohmann::json& json, const std::string& label) {
    try {
        return parse_experiment(json, label);
    } catch (const ValidationError& e) {
        throw WireError(
            label + ": " +
            (e.problems.empty() ? std::string(e.what()) : e.problems.front().to_string()));
    }
}

}  // namespace

std::string encode_rules(const RulesMessage& message) {
    const nlohmann::json json = experiment_to_json(message.rules);
    // The evaluating ranks simulate what they parse: refuse anything the JSON would change.
    if (rules_from_json(json, "rules") != message.rules)
        throw WireError("the experiment '" + message.rules.name +
                        "' does not survive its JSON round trip; it cannot be sent to other ranks");
    Writer out(Kind::Rules);
    out.u64(message.rules_id);
    const std::string text = json.dump();
    out.raw(text.data(), text.size());
    return out.take();
}

RulesMessage decode_rules(const std::string& bytes) {
    Reader in(bytes, Kind::Rules);
    RulesMessage m;
    m.rules_id = in.u64();
    m.rules = rules_from_json(parse_json(in), in.what());
    return m;
}

std::string encode_job(const JobMessage& message) {
    const Body& body = message.body;
    if (static_cast<std::size_t>(body.cell_count()) != body.cells.size())
        throw WireError("job: body size and cell count disagree");
    Writer out(Kind::Job);
    out.u64(message.batch_id);
    out.u64(message.rules_id);
    out.u32(message.index);
    for (int n : body.size)
        out.i32(n);
    out.raw(body.cells.data(), body.cells.size());
    // Per-voxel fibre axes: a flag, then one byte per cell when the body has them.
    const bool fibres = !body.fibre.empty();
    if (fibres && body.fibre.size() != body.cells.size())
        throw WireError("job: body fibre axes and cell count disagree");
    const std::uint8_t flag = fibres ? 1 : 0;
    out.raw(&flag, 1);
    if (fibres) out.raw(body.fibre.data(), body.fibre.size());
    // A controller's phase and amplitude (issue 44): a flag, then two floats per cell.
    const bool controller = body.has_controller();
    if (controller &&
        (body.phase.size() != body.cells.size() || body.amplitude.size() != body.cells.size()))
        throw WireError("job: body controller and cell count disagree");
    const std::uint8_t controller_flag = controller ? 1 : 0;
    out.raw(&controller_flag, 1);
    if (controller) {
        out.raw(body.phase.data(), body.phase.size() * sizeof(float));
        out.raw(body.amplitude.data(), body.amplitude.size() * sizeof(float));
    }
    return out.take();
}

JobMessage decode_job(const std::string& bytes) {
    Reader in(bytes, Kind::Job);
    JobMessage m;
    m.batch_id = in.u64();
    m.rules_id = in.u64();
    m.index = in.u32();
    for (auto& n : m.body.size) {
        n = in.i32();
        if (n < 0 || n > 4096) throw WireError(in.what() + ": body size out of range");
    }
    m.body.cells.resize(static_cast<std::size_t>(m.body.cell_count()));
    in.raw(m.body.cells.data(), m.body.cells.size());
    std::uint8_t fibres = 0;
    in.raw(&fibres, 1);
    if (fibres > 1) throw WireError(in.what() + ": bad fibre flag");
    if (fibres) {
        m.body.fibre.resize(m.body.cells.size());
        in.raw(m.body.fibre.data(), m.body.fibre.size());
    }
    std::uint8_t controller = 0;
    in.raw(&controller, 1);
    if (controller > 1) throw WireError(in.what() + ": bad controller flag");
    if (controller) {
        m.body.phase.resize(m.body.cells.size());
        m.body.amplitude.resize(m.body.cells.size());
        in.raw(m.body.phase.data(), m.body.phase.size() * sizeof(float));
        in.raw(m.body.amplitude.data(), m.body.amplitude.size() * sizeof(float));
    }
    in.done();
    return m;
}

std::string encode_result(const ResultMessage& message) {
    Writer out(Kind::Result);
    out.u64(message.batch_id);
    out.u32(message.index);
    const std::string text = report_to_json(message.report).dump();
    out.raw(text.data(), text.size());
    return out.take();
}

ResultMessage decode_result(const std::string& bytes) {
    Reader in(bytes, Kind::Result);
    ResultMessage m;
    m.batch_id = in.u64();
    m.index = in.u32();
    const auto json = parse_json(in);
    try {
        m.report = report_from_json(json, in.what());
    } catch (const std::runtime_error& e) {
        throw WireError(e.what());
    }
    return m;
}

}  // namespace bhm::evo
