#include "app/gui/actions/export_geometry.hpp"

#include <filesystem>

#include "app/gui/actions/studio_actions.hpp"
#include "engine/io/text_file.hpp"
#include "evo/experiment/experiment_io.hpp"
#include "evo/formats/surface_mesh.hpp"
#include "evo/formats/vtk_series.hpp"

namespace bhm::app::gui {

namespace {

bool ends_with_either(const std::string& path, const char* lower, const char* upper) {
    for (const std::string suffix : {lower, upper})
        if (path.size() >= suffix.size() &&
            path.compare(path.size() - suffix.size(), suffix.size(), suffix) == 0)
            return true;
    return false;
}

}  // namespace

bool export_mesh(Studio& s, const std::string& path, bool deformed) {
    const bool stl = ends_with_either(path, ".stl", ".STL");
    if (!stl && !ends_with_either(path, ".obj", ".OBJ")) {
        set_status(s, "mesh: the file name ends in .stl or .obj, got '" + path + "'", true);
        return false;
    }
    try {
        evo::SurfaceMesh mesh;
        const evo::Experiment* experiment = nullptr;
        std::string when = "at rest";
        if (deformed) {
            if (!s.bodies.shown || s.bodies.shown->replay.frames.empty()) {
                set_status(s, "mesh: no simulated body is shown to deform", true);
                return false;
            }
            const double t = s.clock.time_s;
            mesh = evo::deformed_surface(s.bodies.shown->replay,
                                         engine::pose_at(s.bodies.shown->replay, t));
            experiment = &s.bodies.shown->experiment;
            when = "at t = " + engine::format_number(t) + " s";
        } else if (s.bodies.shown) {
            const evo::Body& b = *s.bodies.shown->framed_body;
            experiment = &s.bodies.shown->experiment;
            mesh = evo::rest_surface(b.size, b.cells, experiment->voxel_size_m);
        } else if (s.run.snapshot && s.run.snapshot->has_champion &&
                   s.run.snapshot->champion.body) {
            const evo::Body& b = *s.run.snapshot->champion.body;
            experiment = &s.run.snapshot->experiment;
            mesh = evo::rest_surface(b.size, b.cells, experiment->voxel_size_m);
        } else {
            set_status(s, "mesh: no champion or simulated body yet", true);
            return false;
        }
        std::error_code ec;
        const auto parent = std::filesystem::path(path).parent_path();
        if (!parent.empty()) std::filesystem::create_directories(parent, ec);
        if (stl) {
            evo::write_file_atomically(path, evo::stl_binary(mesh));
        } else {
            const auto mtl = std::filesystem::path(path).replace_extension(".mtl");
            evo::write_file_atomically(mtl.string(), evo::mtl_document(experiment->materials));
            evo::write_file_atomically(
                path, evo::obj_document(mesh, experiment->materials, mtl.filename().string()));
        }
        set_status(s, "mesh written (" + std::to_string(mesh.triangles.size()) + " triangles, " +
                          when + "): " + std::filesystem::absolute(path).string());
        return true;
    } catch (const std::exception& e) {
        set_status(s, e.what(), true);
        return false;
    }
}

bool export_vtk_series(Studio& s, const std::string& dir) {
    if (!s.bodies.shown || s.bodies.shown->replay.frames.empty()) {
        set_status(s, "ParaView series: no simulated body is shown", true);
        return false;
    }
    try {
        const auto written = evo::write_vtk_series(dir, s.bodies.shown->replay,
                                                   s.bodies.shown->experiment.materials);
        set_status(s, "ParaView series written (" + std::to_string(written.frames) +
                          " frames): " + std::filesystem::absolute(written.pvd_path).string());
        return true;
    } catch (const std::exception& e) {
        set_status(s, e.what(), true);
        return false;
    }
}

}  // namespace bhm::app::gui
