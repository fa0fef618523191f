// Controller CPPNs and built-in controllers painted onto a body (controller.hpp).
#include "evo/genome/controller.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "evo/genome/cppn_decoder.hpp"
#include "evo/genome/hyperneat_substrate.hpp"

namespace bhm::evo {

namespace {

constexpr double kPi = std::numbers::pi;

// The same stateless hash as make_body_spec's random phase: a cell's phase depends only on the
// seed and the cell.
std::uint64_t mix64(std::uint64_t x) {
    x += 0x9E3779B97F4A7C15ULL;
    x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ULL;
    x = (x ^ (x >> 27)) * 0x94D049BB133111EBULL;
    return x ^ (x >> 31);
}

bool active_cell(const Body& body, std::size_t c, const std::vector<MaterialEntry>& materials) {
    const std::uint8_t m = body.cells[c];
    return m != 0 && m <= materials.size() && materials[m - 1u].active();
}

void reset(Body& body) {
    body.phase.assign(body.cells.size(), 0.0f);
    body.amplitude.assign(body.cells.size(), 1.0f);
}

}  // namespace

float controller_phase(double output) {
    return static_cast<float>(std::remainder(kPi * output, 2.0 * kPi));
}

float controller_amplitude(double output) {
    return static_cast<float>(std::clamp(0.5 * (1.0 + output), 0.0, 1.0));
}

Genome random_controller(const CppnSettings& settings, Rng& rng) {
    return random_genome(settings, rng, kControllerOutputCount);
}

void paint_controller(const Genome& controller, const std::vector<MaterialEntry>& materials,
                      Body& body) {
    if (controller.output_count != kControllerOutputCount)
        throw std::invalid_argument("controller genome has " +
                                    std::to_string(controller.output_count) +
                                    " outputs, expected 2 (phase, amplitude)");
    const auto value = cppn_node_values(controller, cppn_inputs(body.size));
    const auto first = static_cast<std::size_t>(controller.input_count);
    paint_controller_outputs(value[first], value[first + 1], materials, body);
}

void paint_controller_outputs(const std::vector<double>& phase,
                              const std::vector<double>& amplitude,
                              const std::vector<MaterialEntry>& materials, Body& body) {
    if (phase.size() != body.cells.size() || amplitude.size() != body.cells.size())
        throw std::invalid_argument("controller outputs: one value per cell of the body expected");
    reset(body);
    for (std::size_t c = 0; c < body.cells.size(); ++c)
        if (active_cell(body, c, materials)) {
            body.phase[c] = controller_phase(phase[c]);
            body.amplitude[c] = controller_amplitude(amplitude[c]);
        }
}

void paint_builtin_controller(const std::string& name, std::uint64_t seed,
                              const std::vector<MaterialEntry>& materials, Body& body) {
    if (name != "uniform" && name != "random" && name != "wave")
        throw std::invalid_argument("unknown built-in controller '" + name +
                                    "' (uniform, random, wave)");
    reset(body);
    // wave: one period over the body's extent along x (its filled cells' bounding box).
    int x_min = body.size[0], x_max = -1;
    for (int z = 0; z < body.size[2]; ++z)
        for (int y = 0; y < body.size[1]; ++y)
            for (int x = 0; x < body.size[0]; ++x)
                if (body.cells[static_cast<std::size_t>(body.index(x, y, z))]) {
                    x_min = std::min(x_min, x);
                    x_max = std::max(x_max, x);
                }
    const double length = std::max(1, x_max - x_min + 1);
    for (int z = 0; z < body.size[2]; ++z)
        for (int y = 0; y < body.size[1]; ++y)
            for (int x = 0; x < body.size[0]; ++x) {
                const auto c = static_cast<std::size_t>(body.index(x, y, z));
                if (!active_cell(body, c, materials)) continue;
                double phase = 0.0;
                if (name == "random")
                    phase = 2.0 * kPi *
                                (static_cast<double>(mix64(seed ^ mix64(c)) >> 11) * 0x1.0p-53) -
                            kPi;
                else if (name == "wave")
                    phase = std::remainder(2.0 * kPi * (x - x_min) / length, 2.0 * kPi);
                body.phase[c] = static_cast<float>(phase);
            }
}

void paint_controller_entry(const ControllerEntry& entry, double weight_range,
                            const std::vector<MaterialEntry>& materials, Body& body) {
    if (entry.genome_json.empty()) {
        paint_builtin_controller(entry.name, entry.seed, materials, body);
        return;
    }
    paint_controller_program(
        controller_program_from_json(nlohmann::json::parse(entry.genome_json), weight_range),
        materials, body);
}

nlohmann::json controller_to_json(const Genome& controller) {
    nlohmann::json genome = genome_to_json(controller);
    genome["outputs"] = {"phase", "amplitude"};
    return {{"format", kControllerFileFormat},
            {"format_version", 1},
            {"phase", "pi * output 0, wrapped onto [-pi, pi]"},
            {"amplitude", "clamp((1 + output 1) / 2, 0, 1)"},
            {"genome", genome}};
}

namespace {

//! The wrapper's format fields, when the object is a controller file rather than a bare genome.
void check_controller_format(const nlohmann::json& json) {
    if (!json.contains("format") || json["format"] != kControllerFileFormat)
        throw std::invalid_argument(std::string("controller.format: expected \"") +
                                    kControllerFileFormat + "\"");
    if (!json.contains("format_version") || json["format_version"] != 1)
        throw std::invalid_argument("controller.format_version: expected 1");
}

//! controller.substrate: the HyperNEAT settings a HyperNEAT CPPN paints with.
HyperNeatSettings substrate_from_json(const nlohmann::json& json) {
    if (!json.is_object()) throw std::invalid_argument("controller.substrate: expected an object");
    HyperNeatSettings s;
    auto integer = [&](const char* key, int& out) {
        if (!json.contains(key) || !json[key].is_number_integer())
            throw std::invalid_argument(std::string("controller.substrate.") + key +
                                        ": expected an integer >= 1");
        const auto v = json[key].get<long long>();
        if (v < 1 || v > 1000)
            throw std::invalid_argument(std::string("controller.substrate.") + key +
                                        ": expected an integer in [1, 1000]");
        out = static_cast<int>(v);
    };
    integer("radius", s.radius);
    integer("steps", s.steps);
    if (!json.contains("weight_threshold") || !json["weight_threshold"].is_number() ||
        !(json["weight_threshold"].get<double>() >= 0.0) ||
        !std::isfinite(json["weight_threshold"].get<double>()))
        throw std::invalid_argument(
            "controller.substrate.weight_threshold: expected a finite number >= 0");
    s.weight_threshold = json["weight_threshold"].get<double>();
    return s;
}

}  // namespace

Genome controller_from_json(const nlohmann::json& json, double weight_range) {
    if (!json.is_object()) throw std::invalid_argument("controller: expected an object");
    const bool wrapped = json.contains("genome");
    if (wrapped) check_controller_format(json);
    Genome genome = genome_from_json(wrapped ? json["genome"] : json, weight_range);
    if (genome.input_count != kInputCount)
        throw std::invalid_argument(
            "controller.genome.inputs: expected the five lattice inputs (x, y, z, d, bias); a "
            "HyperNEAT CPPN paints a substrate (docs/hyperneat.md), not a controller");
    if (genome.output_count != kControllerOutputCount)
        throw std::invalid_argument("controller.genome.outputs: expected 2 (phase, amplitude)");
    return genome;
}

nlohmann::json controller_to_json(const Genome& hyperneat_cppn,
                                  const HyperNeatSettings& substrate) {
    nlohmann::json genome = genome_to_json(hyperneat_cppn);
    genome["outputs"] = {"w_input_hidden", "w_hidden_hidden", "w_hidden_phase",
                         "w_hidden_amplitude"};
    return {{"format", kControllerFileFormat},
            {"format_version", 1},
            {"phase", "pi * the substrate's phase sheet, wrapped onto [-pi, pi]"},
            {"amplitude", "clamp((1 + the substrate's amplitude sheet) / 2, 0, 1)"},
            {"substrate",
             {{"radius", substrate.radius},
              {"steps", substrate.steps},
              {"weight_threshold", substrate.weight_threshold}}},
            {"genome", genome}};
}

ControllerProgram controller_program_from_json(const nlohmann::json& json, double weight_range) {
    if (!json.is_object() || !json.contains("substrate"))
        return {controller_from_json(json, weight_range), std::nullopt};
    check_controller_format(json);
    if (!json.contains("genome")) throw std::invalid_argument("controller.genome: missing");
    ControllerProgram program{genome_from_json(json["genome"], weight_range),
                              substrate_from_json(json["substrate"])};
    if (program.genome.input_count != kHyperNeatInputCount)
        throw std::invalid_argument(
            "controller.genome.inputs: a controller with a substrate needs a HyperNEAT CPPN's " +
            std::to_string(kHyperNeatInputCount) + " inputs (docs/hyperneat.md)");
    if (program.genome.output_count != kSubstrateHiddenOutputs + kControllerOutputCount)
        throw std::invalid_argument(
            "controller.genome.outputs: expected 4 (input -> hidden, hidden -> hidden, hidden -> "
            "phase, hidden -> amplitude)");
    return program;
}

void paint_controller_program(const ControllerProgram& program,
                              const std::vector<MaterialEntry>& materials, Body& body) {
    if (!program.substrate) {
        paint_controller(program.genome, materials, body);
        return;
    }
    const double field = 2.0 * program.substrate->radius + 1.0;
    const double connections = static_cast<double>(body.cells.size()) * field * field * field;
    if (connections > kMaxHyperNeatConnections)
        throw std::invalid_argument(
            "controller.substrate.radius: over a " + std::to_string(body.size[0]) + "x" +
            std::to_string(body.size[1]) + "x" + std::to_string(body.size[2]) +
            " lattice the substrate would have more than 2e6 connections per sheet");
    const HyperNeatSubstrate substrate(body.size, kControllerOutputCount, *program.substrate);
    const auto out = substrate.activate(program.genome);
    paint_controller_outputs(out[0], out[1], materials, body);
}

}  // namespace bhm::evo
