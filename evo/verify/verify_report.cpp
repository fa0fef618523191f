#include "evo/verify/verify_report.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <numeric>
#include <sstream>
#include <stdexcept>

#include "evo/experiment/experiment_io.hpp"
#include "evo/experiment/json_fields.hpp"

namespace bhm::evo {

namespace {

nlohmann::json optional_json(const std::optional<double>& v) {
    return v ? nlohmann::json(*v) : nlohmann::json(nullptr);
}

nlohmann::json measures_json(const ResponseMeasures& m) {
    return {{"tip_displacement_m", m.tip_m},
            {"bend_angle_deg", m.bend_deg},
            {"com_yz_displacement_m", m.com_yz_m},
            {"com_displacement_m", m.com_m}};
}

nlohmann::json differences_json(const LoadComparison& c) {
    nlohmann::json j;
    for (VerifyMeasure m : kVerifyMeasures)
        j[verify_measure_key(m)] = optional_json(c.differences.of(m));
    return j;
}

nlohmann::json floors_json(const LoadComparison& c, const MeasureFloors& floors) {
    nlohmann::json j;
    for (VerifyMeasure m : kVerifyMeasures)
        j[verify_measure_key(m)] = above_floor(c, m, floors);
    return j;
}

std::vector<double> ranks(const std::vector<double>& v) {
    std::vector<std::size_t> order(v.size());
    std::iota(order.begin(), order.end(), 0);
    std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return v[a] < v[b]; });
    std::vector<double> r(v.size());
    for (std::size_t i = 0; i < order.size();) {
        std::size_t j = i;
        while (j + 1 < order.size() && v[order[j + 1]] == v[order[i]]) ++j;
        for (std::size_t k = i; k <= j; ++k)
            r[order[k]] = 0.5 * static_cast<double>(i + j) + 1.0;
        i = j + 1;
    }
    return r;
}

}  // namespace

double spearman(const std::vector<double>& a, const std::vector<double>& b) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    if (a.size() != b.size() || a.size() < 2) return nan;
    const auto ra = ranks(a), rb = ranks(b);
    const double n = static_cast<double>(a.size());
    const double ma = std::accumulate(ra.begin(), ra.end(), 0.0) / n;
    const double mb = std::accumulate(rb.begin(), rb.end(), 0.0) / n;
    double sab = 0.0, saa = 0.0, sbb = 0.0;
    for (std::size_t i = 0; i < ra.size(); ++i) {
        sab += (ra[i] - ma) * (rb[i] - mb);
        saa += (ra[i] - ma) * (ra[i] - ma);
        sbb += (rb[i] - mb) * (rb[i] - mb);
    }
    if (saa == 0.0 || sbb == 0.0) return nan;
    return sab / std::sqrt(saa * sbb);
}

nlohmann::json verification_to_json(const BodyVerification& v, const VerifyOptions& options) {
    nlohmann::json j;
    j["verdict"] = v.verdict();
    if (!v.laws().empty()) j["law"] = v.laws();
    j["status"] = v.status == VerifyStatus::Compared ? "compared" : "out_of_reach";
    j["voxels"] = v.voxels;
    j["held_voxels"] = v.held_voxels;
    j["active_voxels"] = v.active_voxels;
    if (v.status == VerifyStatus::OutOfReach) {
        j["reason"] = v.reason;
        return j;
    }
    j["agrees"] = v.agrees;
    j["tolerance"] = v.tolerance;
    j["worst_relative_difference"] = v.worst;  // the deciding measure's (verdict.hpp)
    j["worst_relative_difference_any_measure"] = v.worst_any;
    j["experiment_measure"] = verify_measure_key(v.measure);
    j["decided_by"] = v.decision.decided_by
                          ? nlohmann::json(verify_measure_key(*v.decision.decided_by))
                          : nlohmann::json(nullptr);
    j["floors"] = {{"bend_angle_deg", v.floors.bend_deg},
                   {"displacement_fraction_of_largest", v.floors.displacement_fraction}};
    nlohmann::json measures = nlohmann::json::array();
    for (const auto& m : v.decision.measures)
        measures.push_back({{"measure", verify_measure_key(m.measure)},
                            {"worst_judged", optional_json(m.judged)},
                            {"worst_any", optional_json(m.any)},
                            {"fem_largest", m.fem_largest}});
    j["measures"] = measures;
    j["tip_cell"] = v.tip_cell;
    j["fem"] = {{"solver", "CalculiX ccx"},
                {"element", fem_element_name(v.mesh.mesh.element)},
                {"elements_per_voxel_edge", v.mesh.mesh.subdivision},
                {"mesh_choice", v.mesh.automatic ? "automatic" : "explicit"},
                {"mesh_reason", v.mesh.reason},
                {"nlgeom", v.nlgeom},
                {"geometry_choice", options.geometry == FemGeometry::Automatic ? "automatic"
                                    : options.geometry == FemGeometry::Linear  ? "linear"
                                                                               : "nonlinear"},
                {"geometry_reason", v.geometry_reason},
                {"nlgeom_from_coarse_mesh", v.nlgeom_from_coarse_mesh},
                {"nlgeom_above_deg", options.nlgeom_above_deg},
                {"nlgeom_above_strain", options.nlgeom_above_strain},
                {"nodes", v.fem_nodes},
                {"elements", v.fem_elements},
                {"cpu_s", v.fem_cpu_s},
                {"wall_s", v.fem_wall_s}};
    nlohmann::json solves = nlohmann::json::array();
    for (const FemSolveCost& c : v.fem_solves)
        solves.push_back({{"mesh", c.coarse ? "coarse" : "mesh"},
                          {"nlgeom", c.nlgeom},
                          {"law", c.law.empty() ? nlohmann::json(nullptr) : nlohmann::json(c.law)},
                          {"element", c.element},
                          {"elements", c.elements},
                          {"nodes", c.nodes},
                          {"deck_s", c.deck_s},
                          {"cpu_s", c.cpu_s},
                          {"wall_s", c.wall_s}});
    j["fem"]["solves"] = solves;
    if (!v.material_law.empty()) {
        j["fem"]["material_law"] = v.material_law;
        if (!v.other_law.empty()) {
            j["fem"]["other_law"] = {
                {"law", v.other_law}, {"worst", nullptr}, {"solved", !v.other_law_skipped}};
            if (v.other_law_worst) j["fem"]["other_law"]["worst"] = *v.other_law_worst;
            j["fem"]["law_spread"] = v.law_spread ? nlohmann::json(*v.law_spread) : nullptr;
        }
    }
    if (v.mesh.automatic)
        j["fem"]["narrowest_section"] = {{"voxels", v.mesh.narrowest.width_voxels},
                                         {"at_voxel", v.mesh.narrowest.at},
                                         {"held", v.mesh.narrowest.held},
                                         {"capped", v.mesh.capped},
                                         {"point_clamp", v.mesh.point_clamp}};
    if (v.muscle)
        j["loads_note"] =
            "muscle model: rest and peak activation (a = 1, the muscles' free "
            "strain as CalculiX's orthotropic expansion); a muscle only "
            "contracts, so there is no -A load";
    j["engine"] = {{"method", v.muscle ? "activation held at 1 (stimulated throughout) or 0, floor "
                                         "off, damped until at rest"
                                       : "constant temperature change, floor off, damped until "
                                         "at rest"},
                   {"global_damping_ratio", options.engine.global_damping_ratio},
                   {"rest_tolerance", options.engine.tolerance},
                   {"cpu_s", v.engine_cpu_s},
                   {"largest_voxel_rotation_deg", v.engine_rotation_deg},
                   {"largest_bend_angle_deg", v.engine_bend_deg}};
    j["score"] = {{"fem", v.fem_score}, {"engine", v.engine_score}};
    nlohmann::json loads = nlohmann::json::array();
    for (const auto& c : v.loads) {
        loads.push_back({{"load", c.load},
                         {"temperature_c", c.temperature_c},
                         {"fem", measures_json(c.fem)},
                         {"engine", measures_json(c.engine)},
                         {"fem_voxel_displacement_rms_m", c.fem_rms_m},
                         {"fem_largest_voxel_displacement_m", c.fem_largest_m},
                         {"relative_difference", differences_json(c)},
                         {"above_floor", floors_json(c, v.floors)}});
        if (v.muscle) loads.back()["activation"] = c.temperature_c;
    }
    j["loads"] = loads;
    return j;
}

std::string fem_mesh_vtk(const FemModel& model, const NodalDisplacements& u,
                         const std::string& title) {
    std::ostringstream out;
    char line[160];
    out << "# vtk DataFile Version 3.0\n" << title << "\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS "
        << model.node_count() << " double\n";
    auto displacement = [&](int id) {
        const auto it = u.find(id);
        return it == u.end() ? std::array<double, 3>{} : it->second;
    };
    for (int id = 1; id <= model.node_count(); ++id) {
        const auto p = model.node_position_m(id);
        const auto d = displacement(id);
        std::snprintf(line, sizeof line, "%.9g %.9g %.9g\n", p[0] + d[0], p[1] + d[1], p[2] + d[2]);
        out << line;
    }
    const std::size_t per = model.elements.empty() ? 0 : model.elements.front().size();
    out << "CELLS " << model.elements.size() << " " << model.elements.size() * (per + 1) << "\n";
    for (const auto& e : model.elements) {
        out << per;
        for (int id : e)
            out << " " << id - 1;  // VTK's 20-node hexahedron has Abaqus's node order
        out << "\n";
    }
    out << "CELL_TYPES " << model.elements.size() << "\n";
    for (std::size_t i = 0; i < model.elements.size(); ++i)
        out << (per == 20 ? 25 : 12) << "\n";
    out << "CELL_DATA " << model.elements.size() << "\nSCALARS material int 1\nLOOKUP_TABLE default\n";
    for (int m : model.element_material)
        out << m << "\n";
    out << "POINT_DATA " << model.node_count() << "\nVECTORS displacement double\n";
    for (int id = 1; id <= model.node_count(); ++id) {
        const auto d = displacement(id);
        std::snprintf(line, sizeof line, "%.9g %.9g %.9g\n", d[0], d[1], d[2]);
        out << line;
    }
    return out.str();
}

}  // namespace bhm::evo

namespace bhm::evo {

namespace {

nlohmann::json poses_json(const engine::VoxelPoses& p) {
    return {{"position_m", p.position_m}, {"orientation", p.orientation}, {"size_m", p.size_m}};
}

// where: "FILE: loads[k].fem", so each problem reads "FILE: field: what is wrong".
engine::VoxelPoses poses_from_json(const nlohmann::json& j, std::size_t voxels,
                                   const std::string& where) {
    if (!j.is_object()) throw std::runtime_error(where + ": expected an object");
    engine::VoxelPoses p;
    const std::pair<const char*, std::size_t> fields[] = {
        {"position_m", 3}, {"orientation", 4}, {"size_m", 3}};
    for (const auto& [name, per] : fields) {
        const auto it = j.find(name);
        if (it == j.end() || !it->is_array() || it->size() != per * voxels ||
            !std::all_of(it->begin(), it->end(), [](const auto& x) { return x.is_number(); }))
            throw std::runtime_error(where + "." + name + ": expected " +
                                     std::to_string(per * voxels) + " numbers");
        auto values = it->template get<std::vector<float>>();
        (std::string(name) == "position_m"    ? p.position_m
         : std::string(name) == "orientation" ? p.orientation
                                              : p.size_m) = std::move(values);
    }
    return p;
}

}  // namespace

nlohmann::json verification_shapes_json(const BodyVerification& v) {
    nlohmann::json loads = nlohmann::json::array();
    for (const auto& c : v.loads)
        loads.push_back({{"load", c.load},
                         {"fem", poses_json(c.fem_shape)},
                         {"engine", poses_json(c.engine_shape)}});
    return {{"voxel_cells", v.fem_model.voxel_cells}, {"loads", loads}};
}

VerificationShapes verification_shapes_from_json(const nlohmann::json& j, const std::string& file) {
    // Every field checked before it is read (json_fields.hpp): a damaged file is "FILE: field:
    // what is wrong" in the studio's FEM tab, never nlohmann's "[json.exception...]" (issue 41 R9).
    VerificationShapes out;
    try {
        const Fields f(j, "");
        const auto& cells = f.array("voxel_cells");
        for (const auto& c : cells) {
            if (!c.is_number_integer() || c.get<std::int64_t>() < 0 ||
                c.get<std::int64_t>() > std::numeric_limits<int>::max())
                f.fail("voxel_cells", "expected an array of cell indices");
            out.voxel_cells.push_back(c.get<int>());
        }
        const auto& loads = f.array("loads");
        for (std::size_t k = 0; k < loads.size(); ++k) {
            const Fields load(loads[k], item("loads", k));
            const std::string where = file + ": " + item("loads", k);
            out.loads.push_back(load.string("load"));
            out.fem.push_back(poses_from_json(load.at("fem"), cells.size(), where + ".fem"));
            out.engine.push_back(
                poses_from_json(load.at("engine"), cells.size(), where + ".engine"));
        }
    } catch (const FieldError& e) {
        throw std::runtime_error(file + ": " + e.what());
    }
    return out;
}

nlohmann::json write_verification(const BodyVerification& v, const VerifyOptions& o,
                                  const std::string& dir_text) {
    namespace fs = std::filesystem;
    const fs::path dir = dir_text;
    fs::create_directories(dir);
    nlohmann::json j = verification_to_json(v, o);
    nlohmann::json meshes = nlohmann::json::array();
    for (std::size_t k = 0; k < v.loads.size() && k < v.fem_displacements.size(); ++k) {
        const std::string load = v.loads[k].load;
        const std::string name = "fem-" +
                                 std::string(load == "+A"   ? "plus-A"
                                             : load == "-A" ? "minus-A"
                                                            : load) +  // rest, peak
                                 ".vtk";
        write_file_atomically(
            (dir / name).string(),
            fem_mesh_vtk(v.fem_model, v.fem_displacements[k], "bhm verify: CalculiX at " + load));
        meshes.push_back(name);
    }
    j["fem_meshes"] = meshes;
    if (v.status == VerifyStatus::Compared) {
        write_file_atomically((dir / "shapes.json").string(),
                              verification_shapes_json(v).dump() + "\n");
        j["shapes"] = "shapes.json";
    }
    write_file_atomically((dir / "report.json").string(), j.dump(2) + "\n");
    return j;
}

bool is_verification_file(const std::string& name) {
    const std::string vtk = ".vtk";
    const bool fem_mesh = name.rfind("fem-", 0) == 0 && name.size() > 4 + vtk.size() &&
                          name.compare(name.size() - vtk.size(), vtk.size(), vtk) == 0;
    return name == "report.json" || name == "shapes.json" || fem_mesh;
}

}  // namespace bhm::evo
