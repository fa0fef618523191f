#include "evo/formats/vxa_import.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <stdexcept>

#include "engine/io/text_file.hpp"
#include "evo/experiment/experiment_io.hpp"
#include "evo/experiment/json_reader.hpp"
#include "evo/formats/vxa.hpp"
#include "evo/formats/xml_tree.hpp"

#if BHM_WITH_ZLIB
#include <zlib.h>
#endif

namespace bhm::evo {

namespace {

std::string trim(const std::string& s) {
    const auto begin = s.find_first_not_of(" \t\r\n");
    if (begin == std::string::npos) return "";
    const auto end = s.find_last_not_of(" \t\r\n");
    return s.substr(begin, end - begin + 1);
}

// Reading one VXA file: numbers with the element path in errors, and the list of what is lost.
class VxaReader {
  public:
    explicit VxaReader(std::string label) : label_(std::move(label)) {}

    [[noreturn]] void fail(const std::string& field, const std::string& what) const {
        throw std::runtime_error(label_ + ": " + field + ": " + what);
    }
    void lost(const std::string& what) {
        if (std::find(unmapped_.begin(), unmapped_.end(), what) == unmapped_.end())
            unmapped_.push_back(what);
    }
    std::vector<std::string> take_unmapped() { return std::move(unmapped_); }

    //! The number in parent/tag, or fallback when the element is absent.
    double number(const XmlNode* parent, const std::string& tag, const std::string& path,
                  double fallback) const {
        const XmlNode* node = parent ? parent->child(tag) : nullptr;
        if (!node) return fallback;
        return parse_number(trim(node->text), path + "/" + tag);
    }
    double parse_number(const std::string& text, const std::string& field) const {
        double value = 0.0;
        const char* begin = text.data();
        const char* end = begin + text.size();
        if (!text.empty() && *begin == '+') ++begin;
        const auto result = std::from_chars(begin, end, value);
        if (text.empty() || result.ec != std::errc() || result.ptr != end || !std::isfinite(value))
            fail(field, "expected a number, got '" + text + "'");
        return value;
    }
    bool has(const XmlNode* parent, const std::string& tag) const {
        return parent && parent->child(tag);
    }

    //! Every child of section not in known, with a value other than "0" or empty, is lost.
    void report_unknown(const XmlNode* section, const std::string& path,
                        const std::set<std::string>& known) {
        if (!section) return;
        for (const auto& c : section->children) {
            if (known.count(c->name)) continue;
            const std::string value = trim(c->text);
            if (c->children.empty() && (value.empty() || value == "0")) continue;
            lost(path + "/" + c->name + (c->children.empty() ? " = " + value : "") +
                 ": not used by BHM");
        }
    }

  private:
    std::string label_;
    std::vector<std::string> unmapped_;
};

void read_simulator(VxaReader& r, const XmlNode* sim, Experiment& e, double& stop_s,
                    double& init_cm_s) {
    if (!sim) {
        r.lost("Simulator: missing; BHM's default integration and damping used");
        return;
    }
    const auto* integration = sim->child("Integration");
    if (r.number(integration, "Integrator", "Simulator/Integration", 0.0) != 0.0)
        r.lost("Simulator/Integration/Integrator: only Euler (0) is simulated");
    e.simulation.dt_fraction =
        r.number(integration, "DtFrac", "Simulator/Integration", e.simulation.dt_fraction);
    const auto* damping = sim->child("Damping");
    e.simulation.bond_damping_ratio =
        r.number(damping, "BondDampingZ", "Simulator/Damping", e.simulation.bond_damping_ratio);
    e.simulation.collision_damping_ratio =
        r.number(damping, "ColDampingZ", "Simulator/Damping", e.simulation.collision_damping_ratio);
    e.simulation.global_damping_ratio =
        r.number(damping, "SlowDampingZ", "Simulator/Damping", e.simulation.global_damping_ratio);
    const auto* collisions = sim->child("Collisions");
    if (r.number(collisions, "SelfColEnabled", "Simulator/Collisions", 0.0) != 0.0)
        r.lost("Simulator/Collisions/SelfColEnabled: self-collision is not simulated");
    r.report_unknown(sim->child("Features"), "Simulator/Features", {});
    const auto* stop = sim->child("StopCondition");
    const double type = r.number(stop, "StopConditionType", "Simulator/StopCondition", 2.0);
    if (type == 2.0) {
        stop_s = r.number(stop, "StopConditionValue", "Simulator/StopCondition", -1.0);
    } else {
        r.lost("Simulator/StopCondition/StopConditionType = " + engine::format_number(type) +
               ": only a simulated-time stop (2) maps; BHM's evaluation time used");
    }
    init_cm_s = r.number(stop, "InitCmTime", "Simulator/StopCondition", 0.0);
    r.report_unknown(stop, "Simulator/StopCondition",
                     {"StopConditionType", "StopConditionValue", "InitCmTime"});
    r.report_unknown(
        sim, "Simulator",
        {"Integration", "Damping", "Collisions", "Features", "StopCondition", "SurfMesh"});
}

// Cells overlapped by a box region given in workspace fractions, per axis [first, last].
bool region_cells(const std::array<double, 6>& box, const std::array<int, 3>& n,
                  std::array<std::array<int, 2>, 3>& range) {
    constexpr double eps = 1e-9;
    for (int a = 0; a < 3; ++a) {
        const double lo = box[a], hi = box[a] + box[3 + a];
        int first = n[a], last = -1;
        for (int i = 0; i < n[a]; ++i) {
            const double c0 = static_cast<double>(i) / n[a], c1 = static_cast<double>(i + 1) / n[a];
            if (c1 > lo + eps && c0 < hi - eps) {
                first = std::min(first, i);
                last = std::max(last, i);
            }
        }
        if (last < 0) return false;
        range[a] = {first, last};
    }
    return true;
}

void read_region(VxaReader& r, const XmlNode* region, const std::string& path, bool fixed_list,
                 Experiment& e, const Body& body) {
    const double prim = r.number(region, "PrimType", path, 0.0);
    const double dof = r.number(region, "DofFixed", path, fixed_list ? 63.0 : 0.0);
    for (const char* tag :
         {"ForceX", "ForceY", "ForceZ", "TorqueX", "TorqueY", "TorqueZ", "DisplaceX", "DisplaceY",
          "DisplaceZ", "AngDisplaceX", "AngDisplaceY", "AngDisplaceZ"})
        if (r.number(region, tag, path, 0.0) != 0.0)
            r.lost(path + "/" + tag + ": prescribed forces and displacements are not simulated");
    if (dof == 0.0) return;
    if (dof != 63.0) {
        r.lost(path + "/DofFixed = " + engine::format_number(dof) +
               ": only fully fixed regions (63) map; region ignored");
        return;
    }
    if (prim != 0.0) {
        r.lost(path + "/PrimType = " + engine::format_number(prim) +
               ": only box regions (0) map; region ignored");
        return;
    }
    const std::array<double, 6> box{
        r.number(region, "X", path, 0.0),  r.number(region, "Y", path, 0.0),
        r.number(region, "Z", path, 0.0),  r.number(region, "dX", path, 0.0),
        r.number(region, "dY", path, 0.0), r.number(region, "dZ", path, 0.0)};
    const auto& n = e.workspace_size;
    std::array<std::array<int, 2>, 3> range{};
    if (!region_cells(box, n, range)) {
        r.lost(path + ": the region holds no lattice cell; ignored");
        return;
    }
    // Exactly one face layer, the other two axes whole: a fixed face.
    for (int a = 0; a < 3; ++a) {
        bool others_full = true;
        for (int b = 0; b < 3; ++b)
            if (b != a) others_full &= range[b][0] == 0 && range[b][1] == n[b] - 1;
        if (!others_full || range[a][0] != range[a][1]) continue;
        const bool low = range[a][0] == 0 && box[a] < 0.5;
        const bool high = range[a][0] == n[a] - 1 && !low;
        if (!low && !high) continue;
        e.boundary.faces[static_cast<std::size_t>(2 * a + (high ? 1 : 0))] = BoundaryKind::Fixed;
        return;
    }
    for (int z = range[2][0]; z <= range[2][1]; ++z)
        for (int y = range[1][0]; y <= range[1][1]; ++y)
            for (int x = range[0][0]; x <= range[0][1]; ++x) {
                if (body.cells[static_cast<std::size_t>(body.index(x, y, z))] == 0) continue;
                VoxelOverride o;
                o.voxel = {x, y, z};
                o.kind = OverrideKind::Fixed;
                if (std::find(e.boundary.voxel_overrides.begin(), e.boundary.voxel_overrides.end(),
                              o) == e.boundary.voxel_overrides.end())
                    e.boundary.voxel_overrides.push_back(o);
            }
}

void read_environment(VxaReader& r, const XmlNode* env, Experiment& e, const Body& body) {
    if (!env) {
        r.lost("Environment: missing; BHM's default gravity, floor and actuation used");
        return;
    }
    for (const char* container : {"Boundary_Conditions", "Fixed_Regions"}) {
        const XmlNode* list = env->child(container);
        if (!list) continue;
        int index = 0;
        for (const auto& c : list->children) {
            if (c->name != "FRegion" && c->name != "Region") continue;
            read_region(r, c.get(),
                        std::string("Environment/") + container + "/" + c->name + "[" +
                            std::to_string(index++) + "]",
                        std::string(container) == "Fixed_Regions", e, body);
        }
    }
    if (r.number(env->child("Forced_Regions"), "NumForced", "Environment/Forced_Regions", 0.0) !=
        0.0)
        r.lost("Environment/Forced_Regions: prescribed forces are not simulated");
    const auto* gravity = env->child("Gravity");
    const bool gravity_on = r.number(gravity, "GravEnabled", "Environment/Gravity", 1.0) != 0.0;
    const double g = r.number(gravity, "GravAcc", "Environment/Gravity", -9.81);
    e.environment.gravity_m_s2 = gravity_on ? g : 0.0;
    e.environment.floor = r.number(gravity, "FloorEnabled", "Environment/Gravity", 1.0) != 0.0;
    r.report_unknown(gravity, "Environment/Gravity", {"GravEnabled", "GravAcc", "FloorEnabled"});
    const auto* thermal = env->child("Thermal");
    if (thermal) {
        const bool on = r.number(thermal, "TempEnabled", "Environment/Thermal", 1.0) != 0.0;
        const bool varying =
            r.number(thermal, "VaryTempEnabled", "Environment/Thermal", 1.0) != 0.0;
        const double amplitude =
            r.has(thermal, "TempAmplitude")
                ? r.number(thermal, "TempAmplitude", "Environment/Thermal", 0.0)
                : r.number(thermal, "TempAmp", "Environment/Thermal",
                           e.actuation.temperature_amplitude_c);
        const double period = r.number(thermal, "TempPeriod", "Environment/Thermal", 0.0);
        if (!on || !varying) {
            e.actuation.temperature_amplitude_c = 0.0;
            r.lost("Environment/Thermal: a constant temperature is not simulated; amplitude 0");
        } else {
            e.actuation.temperature_amplitude_c = amplitude;
        }
        if (period > 0.0)
            e.actuation.frequency_hz = 1.0 / period;
        else if (on && varying)
            r.lost("Environment/Thermal/TempPeriod: missing or not positive; BHM's frequency used");
        r.report_unknown(thermal, "Environment/Thermal",
                         {"TempEnabled", "VaryTempEnabled", "TempAmplitude", "TempAmp",
                          "TempPeriod", "TempBase"});
    } else {
        r.lost("Environment/Thermal: missing; BHM's default actuation used");
    }
    r.report_unknown(
        env, "Environment",
        {"Boundary_Conditions", "Fixed_Regions", "Forced_Regions", "Gravity", "Thermal"});
}

// Palette in ID order: material IDs map to 1-based indices 1..K.
std::map<int, int> read_palette(VxaReader& r, const XmlNode* palette, Experiment& e) {
    if (!palette) r.fail("VXC/Palette", "missing");
    std::map<int, const XmlNode*> by_id;
    int next_id = 1;
    for (const auto* m : palette->all("Material")) {
        int id = next_id;
        if (m->attributes.count("ID"))
            id =
                static_cast<int>(r.parse_number(m->attributes.at("ID"), "VXC/Palette/Material@ID"));
        if (id < 1 || by_id.count(id))
            r.fail("VXC/Palette/Material@ID", "duplicate or invalid ID " + std::to_string(id));
        by_id[id] = m;
        next_id = id + 1;
    }
    if (by_id.empty()) r.fail("VXC/Palette", "has no Material");
    std::map<int, int> index_of_id;
    e.materials.clear();
    for (const auto& [id, m] : by_id) {
        const std::string path = "VXC/Palette/Material[ID=" + std::to_string(id) + "]";
        MaterialEntry entry;
        entry.name =
            m->child("Name") ? trim(m->child("Name")->text) : "material " + std::to_string(id);
        if (r.number(m, "MatType", path, 0.0) != 0.0)
            r.lost(path +
                   "/MatType: composite or dependent materials are not simulated; "
                   "read as a plain material");
        const auto* display = m->child("Display");
        if (display) {
            entry.color = {static_cast<float>(r.number(display, "Red", path + "/Display", 0.8)),
                           static_cast<float>(r.number(display, "Green", path + "/Display", 0.8)),
                           static_cast<float>(r.number(display, "Blue", path + "/Display", 0.8))};
            entry.has_color = true;
        }
        const auto* mech = m->child("Mechanical");
        const std::string mpath = path + "/Mechanical";
        auto& p = entry.physics;
        if (r.number(mech, "MatModel", mpath, 0.0) != 0.0)
            r.lost(mpath + "/MatModel: only linear elastic (0) is simulated");
        for (const char* tag : {"Plastic_Mod", "Yield_Stress", "FailModel", "Fail_Stress",
                                "Fail_Strain", "MaterialTempPhase"})
            if (r.number(mech, tag, mpath, 0.0) != 0.0)
                r.lost(mpath + "/" + tag + ": not simulated");
        p.youngs_modulus_pa = r.number(mech, "Elastic_Mod", mpath, p.youngs_modulus_pa);
        p.density_kg_m3 = r.number(mech, "Density", mpath, p.density_kg_m3);
        p.poisson_ratio = r.number(mech, "Poissons_Ratio", mpath, p.poisson_ratio);
        p.cte_per_c = r.number(mech, "CTE", mpath, p.cte_per_c);
        p.static_friction = r.number(mech, "uStatic", mpath, p.static_friction);
        p.dynamic_friction = r.number(mech, "uDynamic", mpath, p.dynamic_friction);
        r.report_unknown(mech, mpath,
                         {"MatModel", "Plastic_Mod", "Yield_Stress", "FailModel", "Fail_Stress",
                          "Fail_Strain", "MaterialTempPhase", "Elastic_Mod", "Density",
                          "Poissons_Ratio", "CTE", "uStatic", "uDynamic"});
        e.materials.push_back(entry);
        index_of_id[id] = static_cast<int>(e.materials.size());
    }
    return index_of_id;
}

std::string decode_base64(const VxaReader& r, const std::string& text, const std::string& field) {
    std::string out;
    unsigned bits = 0;
    int count = 0;
    for (char c : text) {
        int v;
        if (c >= 'A' && c <= 'Z')
            v = c - 'A';
        else if (c >= 'a' && c <= 'z')
            v = c - 'a' + 26;
        else if (c >= '0' && c <= '9')
            v = c - '0' + 52;
        else if (c == '+')
            v = 62;
        else if (c == '/')
            v = 63;
        else if (c == '=' || std::isspace(static_cast<unsigned char>(c)))
            continue;
        else
            r.fail(field, "not base64 (ZLIB layer)");
        bits = (bits << 6) | static_cast<unsigned>(v);
        count += 6;
        if (count >= 8) {
            count -= 8;
            out += static_cast<char>((bits >> count) & 0xffu);
        }
    }
    return out;
}

std::string inflate_layer([[maybe_unused]] const VxaReader& r,
                          [[maybe_unused]] const std::string& text,
                          [[maybe_unused]] std::size_t cells,
                          [[maybe_unused]] const std::string& field) {
#if BHM_WITH_ZLIB
    const std::string packed = decode_base64(r, text, field);
    std::string out(cells + 1, '\0');  // one spare byte: a longer layer is reported, not cut
    uLongf size = static_cast<uLongf>(out.size());
    const int status = ::uncompress(reinterpret_cast<Bytef*>(out.data()), &size,
                                    reinterpret_cast<const Bytef*>(packed.data()),
                                    static_cast<uLong>(packed.size()));
    if (status != Z_OK && status != Z_BUF_ERROR) r.fail(field, "the ZLIB data does not decompress");
    out.resize(status == Z_BUF_ERROR ? cells + 1 : size);
    return out;
#else
    return {};
#endif
}

Body read_structure(VxaReader& r, const XmlNode* structure, const std::map<int, int>& index_of_id) {
    if (!structure) r.fail("VXC/Structure", "missing");
    const std::string compression = structure->attributes.count("Compression")
                                        ? structure->attributes.at("Compression")
                                        : "ASCII_READABLE";
    const bool zlib = compression == "ZLIB";
#if !BHM_WITH_ZLIB
    if (zlib)
        r.fail("VXC/Structure@Compression",
               "ZLIB needs a build with zlib; save the file from VoxCAD with ASCII_READABLE "
               "compression");
#endif
    if (compression != "ASCII_READABLE" && !zlib)
        r.fail("VXC/Structure@Compression",
               "'" + compression +
                   "' is not supported (ASCII_READABLE or ZLIB); save the file from VoxCAD "
                   "with ASCII_READABLE compression");
    Body body;
    const char* axes[3] = {"X_Voxels", "Y_Voxels", "Z_Voxels"};
    for (int a = 0; a < 3; ++a) {
        if (!structure->child(axes[a])) r.fail(std::string("VXC/Structure/") + axes[a], "missing");
        const double n = r.number(structure, axes[a], "VXC/Structure", 0.0);
        if (n < 1 || n > 255 || n != std::floor(n))
            r.fail(std::string("VXC/Structure/") + axes[a], "must be a whole number in [1, 255]");
        body.size[a] = static_cast<int>(n);
    }
    const auto* data = structure->child("Data");
    if (!data) r.fail("VXC/Structure/Data", "missing");
    const auto layers = data->all("Layer");
    if (static_cast<int>(layers.size()) != body.size[2])
        r.fail("VXC/Structure/Data", std::to_string(layers.size()) +
                                         " layers for Z_Voxels = " + std::to_string(body.size[2]));
    const std::size_t per_layer = static_cast<std::size_t>(body.size[0]) * body.size[1];
    for (std::size_t z = 0; z < layers.size(); ++z) {
        const std::string field = "VXC/Structure/Data/Layer[" + std::to_string(z) + "]";
        // ASCII_READABLE: one character '0' + ID per cell. ZLIB (VoxCAD's default): base64 of
        // the zlib-compressed layer, one byte (the ID itself) per cell.
        const std::string text = zlib ? inflate_layer(r, trim(layers[z]->text), per_layer, field)
                                      : trim(layers[z]->text);
        if (text.size() != per_layer)
            r.fail(field, std::to_string(text.size()) +
                              " cells for X_Voxels x Y_Voxels = " + std::to_string(per_layer));
        for (char c : text) {
            const int id = static_cast<unsigned char>(c) - (zlib ? 0 : '0');
            if (id == 0) {
                body.cells.push_back(0);
                continue;
            }
            const auto found = index_of_id.find(id);
            if (id < 0 || found == index_of_id.end())
                r.fail(field, "cell " + std::to_string(id) + " names no palette material");
            body.cells.push_back(static_cast<std::uint8_t>(found->second));
        }
    }
    for (const auto& c : structure->children)
        if (c->name != "X_Voxels" && c->name != "Y_Voxels" && c->name != "Z_Voxels" &&
            c->name != "Data")
            r.lost("VXC/Structure/" + c->name + ": per-voxel layers are not mapped");
    return body;
}

void read_lattice(VxaReader& r, const XmlNode* vxc, Experiment& e) {
    const auto* lattice = vxc->child("Lattice");
    e.voxel_size_m = r.number(lattice, "Lattice_Dim", "VXC/Lattice", e.voxel_size_m);
    for (const char* tag : {"X_Dim_Adj", "Y_Dim_Adj", "Z_Dim_Adj"})
        if (r.number(lattice, tag, "VXC/Lattice", 1.0) != 1.0)
            r.lost(std::string("VXC/Lattice/") + tag + ": only cubic lattices are simulated");
    for (const char* tag : {"X_Line_Offset", "Y_Line_Offset", "X_Layer_Offset", "Y_Layer_Offset"})
        if (r.number(lattice, tag, "VXC/Lattice", 0.0) != 0.0)
            r.lost(std::string("VXC/Lattice/") + tag + ": offset lattices are not simulated");
    const auto* voxel = vxc->child("Voxel");
    if (voxel && voxel->child("Vox_Name") && trim(voxel->child("Vox_Name")->text) != "BOX")
        r.lost("VXC/Voxel/Vox_Name = " + trim(voxel->child("Vox_Name")->text) +
               ": voxels are simulated as boxes");
    for (const char* tag : {"X_Squeeze", "Y_Squeeze", "Z_Squeeze"})
        if (r.number(voxel, tag, "VXC/Voxel", 1.0) != 1.0)
            r.lost(std::string("VXC/Voxel/") + tag + ": squeezed voxels are not simulated");
}

std::string without_space(const std::string& s) {
    std::string out;
    for (char c : s)
        if (!std::isspace(static_cast<unsigned char>(c))) out += c;
    return out;
}

}  // namespace

VxaImport parse_vxa(const std::string& text, const std::string& label) {
    std::unique_ptr<XmlNode> root;
    try {
        root = parse_xml(text);
    } catch (const std::runtime_error& e) {
        throw std::runtime_error(label + ": " + e.what());
    }
    VxaReader r(label);
    if (root->name != "VXA" && root->name != "VXC")
        r.fail(root->name, "the root element is neither VXA nor VXC");
    const XmlNode* vxc = root->name == "VXC" ? root.get() : root->child("VXC");
    if (!vxc) r.fail("VXC", "missing");

    VxaImport out;
    Experiment& e = out.experiment;
    // Our own export carries the whole experiment; if the rest of the file is exactly what we
    // would write for it, it is the experiment (exact round trip).
    // A body's own fibre axes from our export (<BHM_Fibres>, the body file's "fibres" layers),
    // checked as a body file's are.
    auto with_fibres = [&](Body body) {
        const XmlNode* fibres = root->child("BHM_Fibres");
        if (!fibres) return body;
        nlohmann::json file = body_to_json(body);
        try {
            file["fibres"] = nlohmann::json::parse(fibres->text);
        } catch (const nlohmann::json::exception&) {
            r.fail("BHM_Fibres", "not a JSON array of fibre layers");
        }
        return parse_body(file, label + " <BHM_Fibres>");
    };
    if (const XmlNode* ours = root->child("BHM_Experiment")) {
        try {
            const Experiment embedded =
                parse_experiment(nlohmann::json::parse(ours->text), label + " <BHM_Experiment>");
            const std::map<int, int> identity = [&] {
                std::map<int, int> m;
                for (int i = 1; i <= static_cast<int>(embedded.materials.size()); ++i)
                    m[i] = i;
                return m;
            }();
            VxaReader quiet(label);
            const Body body = with_fibres(read_structure(quiet, vxc->child("Structure"), identity));
            if (without_space(vxa_document(embedded, body)) == without_space(text)) {
                out.experiment = embedded;
                out.body = body;
                out.had_bhm_experiment = true;
                return out;
            }
            e = embedded;  // edited since export: its fields are the base, the VXA's win
            r.lost(
                "BHM_Experiment: the file was changed after BHM wrote it; its VoxCAD fields "
                "were read over the embedded experiment");
        } catch (const std::exception& ex) {
            r.lost(std::string("BHM_Experiment: unreadable (") + without_json_tags(ex.what()) +
                   "); ignored");
        }
    } else {
        e.name = std::filesystem::path(label).stem().string();
        e.description = "Imported from " + std::filesystem::path(label).filename().string();
        e.boundary = Boundary{};
    }

    read_lattice(r, vxc, e);
    const auto index_of_id = read_palette(r, vxc->child("Palette"), e);
    out.body = with_fibres(read_structure(r, vxc->child("Structure"), index_of_id));
    e.workspace_size = out.body.size;
    double stop_s = -1.0, init_cm_s = 0.0;
    if (root->name == "VXA") {
        read_simulator(r, root->child("Simulator"), e, stop_s, init_cm_s);
        // The VXA's fixed regions are the whole truth about what is held.
        e.boundary.faces.fill(BoundaryKind::Free);
        std::erase_if(e.boundary.voxel_overrides,
                      [](const VoxelOverride& o) { return o.kind == OverrideKind::Fixed; });
        read_environment(r, root->child("Environment"), e, out.body);
        r.report_unknown(root.get(), "VXA", {"Simulator", "Environment", "VXC", "BHM_Experiment"});
    } else {
        r.lost("VXC only: no simulator or environment settings; BHM's defaults used");
    }
    if (!root->child("BHM_Experiment")) {
        // evosoro measures fitness from InitCmTime on: BHM's settle time plays that part.
        e.simulation.settle_s = init_cm_s > 0.0 ? init_cm_s : 0.0;
        if (e.simulation.settle_s > 0.0)
            r.lost(
                "Simulator/StopCondition/InitCmTime: used as settle_s; VoxCAD actuates from "
                "t = 0, BHM only after settle_s");
    }
    if (stop_s > e.simulation.settle_s) e.simulation.evaluate_s = stop_s - e.simulation.settle_s;
    out.unmapped = r.take_unmapped();
    return out;
}

VxaImport load_vxa(const std::string& path) {
    // A VXA is a few kB to a few MB; the cap keeps a wrong file (a disk image, a 200 MB log)
    // from being parsed into a DOM several times its size.
    return parse_vxa(engine::read_text(path, engine::kTextFileCap), path);
}

}  // namespace bhm::evo
