#include "evo/formats/vxa.hpp"

#include <charconv>
#include <sstream>
#include <stdexcept>

#include "engine/io/text_file.hpp"
#include "evo/experiment/experiment_io.hpp"

namespace bhm::evo {

namespace {

std::string escape_xml(const std::string& text) {
    std::string out;
    for (char c : text) {
        switch (c) {
            case '&':
                out += "&amp;";
                break;
            case '<':
                out += "&lt;";
                break;
            case '>':
                out += "&gt;";
                break;
            case '"':
                out += "&quot;";
                break;
            case '\'':
                out += "&apos;";
                break;
            default:
                out += c;
        }
    }
    return out;
}

//! <tag>value</tag>
std::string element(const char* tag, const std::string& value) {
    return std::string("<") + tag + ">" + value + "</" + tag + ">";
}
std::string element(const char* tag, double value) {
    return element(tag, engine::format_number(value));
}

std::string fixed_region(const Experiment& e, int face) {
    // A box in workspace fractions covering the one-voxel layer at the face.
    const int axis = face / 2;
    const bool high = face % 2 == 1;
    double origin[3] = {0.0, 0.0, 0.0}, extent[3] = {1.0, 1.0, 1.0};
    const double layer = 1.0 / e.workspace_size[static_cast<std::size_t>(axis)];
    extent[axis] = layer;
    origin[axis] = high ? 1.0 - layer : 0.0;
    std::ostringstream o;
    o << "<FRegion>" << element("PrimType", "0") << element("X", origin[0])
      << element("Y", origin[1]) << element("Z", origin[2]) << element("dX", extent[0])
      << element("dY", extent[1]) << element("dZ", extent[2]) << element("Radius", "0")
      << element("R", "0.4") << element("G", "0.6") << element("B", "0.4") << element("alpha", "1")
      << element("DofFixed", "63");
    for (const char* tag :
         {"ForceX", "ForceY", "ForceZ", "TorqueX", "TorqueY", "TorqueZ", "DisplaceX", "DisplaceY",
          "DisplaceZ", "AngDisplaceX", "AngDisplaceY", "AngDisplaceZ"})
        o << element(tag, "0");
    o << "</FRegion>\n";
    return o.str();
}

}  // namespace

std::string vxa_document(const Experiment& e, const Body& body) {
    if (body.cells.size() != static_cast<std::size_t>(body.cell_count()))
        throw std::invalid_argument("VXA export: body cells do not match its size");
    std::ostringstream o;
    o << "<?xml version=\"1.0\" encoding=\"ISO-8859-1\"?>\n<VXA Version=\"1.0\">\n";
    // "--" may not appear inside an XML comment.
    std::string name = e.name;
    for (std::size_t at = name.find("--"); at != std::string::npos; at = name.find("--", at))
        name.replace(at, 2, "- ");
    o << "<!-- Written by BHM Studio for experiment '" << escape_xml(name)
      << "'. VXA 1.0 has no settle delay: BHM starts actuation at t = "
      << engine::format_number(e.simulation.settle_s) << " s. -->\n";
    o << "<Simulator>\n"
      << "<Integration>" << element("Integrator", "0")
      << element("DtFrac", e.simulation.dt_fraction) << "</Integration>\n"
      << "<Damping>" << element("BondDampingZ", e.simulation.bond_damping_ratio)
      << element("ColDampingZ", e.simulation.collision_damping_ratio)
      << element("SlowDampingZ", e.simulation.global_damping_ratio) << "</Damping>\n"
      << "<Collisions>" << element("SelfColEnabled", "0") << element("ColSystem", "3")
      << element("CollisionHorizon", "2") << "</Collisions>\n"
      << "<Features>" << element("FluidDampEnabled", "0") << element("PoissonKickBackEnabled", "0")
      << element("EnforceLatticeEnabled", "0") << "</Features>\n"
      << "<StopCondition>" << element("StopConditionType", "2")
      << element("StopConditionValue", e.simulation.settle_s + e.simulation.evaluate_s)
      << "</StopCondition>\n"
      << "</Simulator>\n";

    o << "<Environment>\n<Boundary_Conditions>\n";
    int fixed_faces = 0;
    for (auto f : e.boundary.faces)
        fixed_faces += f == BoundaryKind::Fixed ? 1 : 0;
    o << element("NumBCs", std::to_string(fixed_faces)) << "\n";
    for (int f = 0; f < 6; ++f)
        if (e.boundary.faces[static_cast<std::size_t>(f)] == BoundaryKind::Fixed)
            o << fixed_region(e, f);
    o << "</Boundary_Conditions>\n"
      << "<Gravity>" << element("GravEnabled", e.environment.gravity_m_s2 != 0.0 ? "1" : "0")
      << element("GravAcc", e.environment.gravity_m_s2)
      << element("FloorEnabled", e.environment.floor ? "1" : "0") << "</Gravity>\n"
      << "<Thermal>" << element("TempEnabled", "1")
      << element("TempAmp", e.actuation.temperature_amplitude_c) << element("TempBase", "25")
      << element("VaryTempEnabled", "1")
      << element("TempPeriod",
                 e.actuation.frequency_hz > 0.0 ? 1.0 / e.actuation.frequency_hz : 0.0)
      << "</Thermal>\n</Environment>\n";

    o << "<VXC Version=\"0.93\">\n"
      << "<Lattice>" << element("Lattice_Dim", e.voxel_size_m) << element("X_Dim_Adj", "1")
      << element("Y_Dim_Adj", "1") << element("Z_Dim_Adj", "1") << element("X_Line_Offset", "0")
      << element("Y_Line_Offset", "0") << element("X_Layer_Offset", "0")
      << element("Y_Layer_Offset", "0") << "</Lattice>\n"
      << "<Voxel>" << element("Vox_Name", "BOX") << element("X_Squeeze", "1")
      << element("Y_Squeeze", "1") << element("Z_Squeeze", "1") << "</Voxel>\n";

    o << "<Palette>\n";
    for (std::size_t i = 0; i < e.materials.size(); ++i) {
        const auto& m = e.materials[i];
        const auto& p = m.physics;
        o << "<Material ID=\"" << i + 1 << "\">" << element("MatType", "0")
          << element("Name", escape_xml(m.name)) << "<Display>"
          << element("Red", double{m.color[0]}) << element("Green", double{m.color[1]})
          << element("Blue", double{m.color[2]}) << element("Alpha", "1")
          << "</Display><Mechanical>" << element("MatModel", "0")
          << element("Elastic_Mod", p.youngs_modulus_pa) << element("Plastic_Mod", "0")
          << element("Yield_Stress", "0") << element("FailModel", "0")
          << element("Fail_Stress", "0") << element("Fail_Strain", "0")
          << element("Density", p.density_kg_m3) << element("Poissons_Ratio", p.poisson_ratio)
          << element("CTE", p.cte_per_c) << element("uStatic", p.static_friction)
          << element("uDynamic", p.dynamic_friction) << "</Mechanical></Material>\n";
    }
    o << "</Palette>\n";

    o << "<Structure Compression=\"ASCII_READABLE\">\n"
      << element("X_Voxels", std::to_string(body.size[0]))
      << element("Y_Voxels", std::to_string(body.size[1]))
      << element("Z_Voxels", std::to_string(body.size[2])) << "\n<Data>\n";
    const std::size_t layer_cells = static_cast<std::size_t>(body.size[0]) * body.size[1];
    for (int z = 0; z < body.size[2]; ++z) {
        std::string layer(layer_cells, '0');
        for (std::size_t c = 0; c < layer_cells; ++c) {
            const int m = body.cells[z * layer_cells + c];
            // '0' + 44 = '\\': the characters stay below ']' so a layer never holds "]]>".
            if (m > 44) throw std::invalid_argument("VXA export: material index above 44");
            layer[c] = static_cast<char>('0' + m);
        }
        o << "<Layer><![CDATA[" << layer << "]]></Layer>\n";
    }
    o << "</Data>\n</Structure>\n</VXC>\n";
    // The whole experiment for BHM's own import (VoxCAD skips elements it does not know); "]]>"
    // inside the JSON is split across two CDATA sections.
    std::string json = experiment_to_json(e).dump();
    const std::string split = "]]]]><![CDATA[>";
    for (std::size_t at = json.find("]]>"); at != std::string::npos;
         at = json.find("]]>", at + split.size()))
        json.replace(at, 3, split);
    o << "<BHM_Experiment><![CDATA[" << json << "]]></BHM_Experiment>\n";
    // A body's own fibre axes (issue 43), which VXA cannot express: the body file's "fibres"
    // layers (only 'x', 'y', 'z', '.', so never "]]>").
    if (const nlohmann::json b = body_to_json(body); b.contains("fibres"))
        o << "<BHM_Fibres><![CDATA[" << b["fibres"].dump() << "]]></BHM_Fibres>\n";
    o << "</VXA>\n";
    return o.str();
}

void save_vxa(const std::string& path, const Experiment& experiment, const Body& body) {
    write_file_atomically(path, vxa_document(experiment, body));
}

}  // namespace bhm::evo
