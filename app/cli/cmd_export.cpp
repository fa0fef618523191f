// bhm export: a body, or a run's champion, as a VoxCAD VXA file, a body JSON or an experiment JSON,
// its surface as an STL/OBJ mesh (at rest or deformed at a replay time), or a replay as a ParaView
// series. The formats live in evo/ (vxa, surface_mesh, vtk_series); this file only wires them.
#include <filesystem>
#include <fstream>
#include <iostream>
#include <optional>
#include <sstream>
#include <string>
#include <vector>
#include <stdexcept>

#include "app/cli/arg_parser.hpp"
#include "app/cli/commands.hpp"
#include "app/cli/problem_report.hpp"
#include "engine/io/atomic_file.hpp"
#include "engine/io/staged_folder.hpp"
#include "engine/io/text_file.hpp"
#include "engine/replay.hpp"
#include "evo/experiment/body_spec_of.hpp"
#include "evo/experiment/experiment_io.hpp"
#include "evo/formats/surface_mesh.hpp"
#include "evo/formats/vtk_series.hpp"
#include "evo/formats/vxa.hpp"
#include "evo/run/run_directory.hpp"

namespace bhm::app {

namespace {

bool ends_with(const std::string& text, const std::string& suffix) {
    return text.size() >= suffix.size() &&
           text.compare(text.size() - suffix.size(), suffix.size(), suffix) == 0;
}

engine::Replay load_matching_replay(const std::string& path, const evo::Experiment& experiment) {
    engine::Replay replay = engine::read_replay(path);  // throws naming the file
    if (replay.frames.empty()) throw std::runtime_error(path + ": the replay has no frames");
    const auto& w = experiment.workspace_size;
    if (replay.nx != w[0] || replay.ny != w[1] || replay.nz != w[2])
        throw std::runtime_error(path + ": lattice " + std::to_string(replay.nx) + "x" +
                                 std::to_string(replay.ny) + "x" + std::to_string(replay.nz) +
                                 " is not the experiment's workspace " + std::to_string(w[0]) +
                                 "x" + std::to_string(w[1]) + "x" + std::to_string(w[2]));
    for (auto m : replay.voxel_material)
        if (m < 1 || m > experiment.materials.size())
            throw std::runtime_error(path + ": voxel material " + std::to_string(m) +
                                     " is not in the experiment's palette");
    return replay;
}

// Every file of the command is tried before the first one is written (issue 26 N5): a later
// output that cannot be written (a folder in its place, a read-only file system, the .mtl beside
// an .obj) must not leave the earlier ones replaced and the command half done. Trying means
// creating and removing the very temporary the atomic writer will use.
void require_all_writable(ArgParser& parser) {
    std::vector<std::string> files;
    for (const char* option : {"--vxa", "--body-out", "--experiment-out", "--mesh"})
        if (parser.has(option)) files.push_back(parser.get(option));
    if (parser.has("--mesh") && !ends_with(parser.get("--mesh"), ".stl") &&
        !ends_with(parser.get("--mesh"), ".STL"))
        files.push_back(
            std::filesystem::path(parser.get("--mesh")).replace_extension(".mtl").string());
    if (parser.has("--vtk") && std::filesystem::is_directory(parser.get("--vtk")))
        files.push_back((std::filesystem::path(parser.get("--vtk")) / "series.pvd").string());
    for (const auto& file : files) {
        if (std::filesystem::is_directory(file))
            throw std::runtime_error(file +
                                     ": is a folder, cannot write a file there; nothing "
                                     "was written");
        try {
            engine::AtomicFile probe(file);  // removed again when it goes out of scope
        } catch (const std::exception& e) {
            throw std::runtime_error(std::string(e.what()) + "; nothing was written");
        }
    }
}

// The surface at rest, or deformed at --time (default: the replay's last frame).
// Written under staged names; the lines to print once they are in place go to written.
void write_mesh(ArgParser& parser, const evo::Experiment& experiment, const evo::Body& framed,
                const engine::Replay* replay, engine::StagedFiles& staged,
                std::vector<std::string>& written) {
    const std::string path = parser.get("--mesh");
    evo::SurfaceMesh mesh;
    std::string when = "at rest";
    if (replay) {
        const double t = parser.get_double("--time", replay->frames.back().time_s);
        mesh = evo::deformed_surface(*replay, engine::pose_at(*replay, t));
        when = "at t = " + engine::format_number(t) + " s";
    } else {
        mesh = evo::rest_surface(framed.size, framed.cells, experiment.voxel_size_m);
    }
    if (ends_with(path, ".stl") || ends_with(path, ".STL")) {
        evo::write_file_atomically(staged.stage(path), evo::stl_binary(mesh));
    } else {
        const std::filesystem::path mtl = std::filesystem::path(path).replace_extension(".mtl");
        evo::write_file_atomically(staged.stage(mtl.string()),
                                   evo::mtl_document(experiment.materials));
        evo::write_file_atomically(
            staged.stage(path),
            evo::obj_document(mesh, experiment.materials, mtl.filename().string()));
        written.push_back(mtl.string());
    }
    std::ostringstream line;
    line << path << " (" << mesh.triangles.size() << " triangles, " << mesh.vertices.size()
         << " vertices, enclosed volume " << engine::format_number(evo::enclosed_volume(mesh))
         << " m^3, " << when << ")";
    written.push_back(line.str());
}

int export_body(ArgParser& parser) {
    namespace fs = std::filesystem;
    const std::string source = parser.positionals().front();
    evo::Experiment experiment;
    evo::Body body;
    if (fs::is_directory(source)) {
        if (parser.has("--body"))
            throw UsageError("--body is for an experiment file; a run directory has its champion");
        // The champion was judged under the rules in force at the end (the last rule change).
        const evo::RunInfo info = evo::read_run_info(source);
        for (const auto& w : info.warnings)
            std::cerr << "bhm export: warning: " << w << "\n";
        experiment = info.current();
        body = evo::read_champion_file(source, experiment).body;
    } else {
        if (!parser.has("--body")) throw UsageError("an experiment file needs --body BODY.json");
        experiment = evo::load_experiment(source);
        say_library_warnings(experiment);
        body = evo::load_body(parser.get("--body"));
        auto problems = evo::validate_body_against(body, experiment, parser.get("--body"));
        if (!problems.empty()) throw evo::ValidationError(problems);
        body = evo::apply_frame_and_overrides(experiment, body);
    }
    if (!parser.has("--vxa") && !parser.has("--body-out") && !parser.has("--experiment-out") &&
        !parser.has("--mesh") && !parser.has("--vtk"))
        throw UsageError(
            "nothing to write: give --vxa, --body-out, --experiment-out, --mesh and/or --vtk");
    if (parser.has("--mesh")) {
        const std::string mesh = parser.get("--mesh");
        if (!ends_with(mesh, ".stl") && !ends_with(mesh, ".STL") && !ends_with(mesh, ".obj") &&
            !ends_with(mesh, ".OBJ"))
            throw UsageError("--mesh wants a FILE.stl or FILE.obj, got '" + mesh + "'");
    }
    if (parser.has("--time") && !parser.has("--replay"))
        throw UsageError("--time needs --replay REPLAY.bin");
    if (parser.has("--time") && !(parser.get_double("--time", 0.0) >= 0.0))
        throw UsageError("--time must be >= 0");
    const long long every = parser.get_int("--vtk-every", 1);
    if (every < 1 || every > 1000000) throw UsageError("--vtk-every must be >= 1");
    std::optional<engine::Replay> replay;
    if (parser.has("--replay")) {
        replay = load_matching_replay(parser.get("--replay"), experiment);
        const double last = replay->frames.back().time_s;
        if (parser.get_double("--time", 0.0) > last + 1e-9)
            throw std::runtime_error(parser.get("--replay") + ": --time " + parser.get("--time") +
                                     " is after the replay's end at " +
                                     engine::format_number(last) + " s");
    }
    require_all_writable(parser);
    // All or nothing (issue 41 R6): every file is written whole under a staged name beside it
    // first; a write that fails then (a full disk, an I/O error) removes the staged ones and
    // leaves every output as it was. The VTK series, a folder staged on its own, goes last
    // before the files are renamed into place.
    std::vector<std::string> written;  // the lines "wrote ..." once all are in place
    {
        engine::StagedFiles staged;
        try {
            if (parser.has("--vxa")) {
                evo::save_vxa(staged.stage(parser.get("--vxa")), experiment, body);
                written.push_back(parser.get("--vxa"));
            }
            if (parser.has("--body-out")) {
                evo::save_body(staged.stage(parser.get("--body-out")), body);
                written.push_back(parser.get("--body-out"));
            }
            if (parser.has("--experiment-out")) {
                evo::save_experiment(staged.stage(parser.get("--experiment-out")), experiment);
                written.push_back(parser.get("--experiment-out"));
            }
            if (parser.has("--mesh"))
                write_mesh(parser, experiment, body, replay ? &*replay : nullptr, staged,
                           written);
            if (parser.has("--vtk")) {
                const engine::Replay series =
                    replay ? *replay : evo::rest_replay(evo::make_body_spec(experiment, body));
                const auto summary = evo::write_vtk_series(
                    parser.get("--vtk"), series, experiment.materials, static_cast<int>(every));
                written.push_back(summary.pvd_path + " (" + std::to_string(summary.frames) +
                                  " frames) and " + summary.com_path);
            }
        } catch (const std::runtime_error& e) {
            throw std::runtime_error(staged.as_final(e.what()) + "; nothing was written");
        }
        staged.commit();
    }
    for (const auto& file : written) std::cout << "wrote " << file << "\n";
    return 0;
}

int run_export(ArgParser& parser) {
    try {
        return export_body(parser);
    } catch (const evo::ValidationError& e) {
        return report_problems(e.problems);
    }
}

}  // namespace

int cmd_export(const Args& args) {
    ArgParser parser(
        "export",
        "(EXPERIMENT.json --body BODY.json | RUN_DIR) [--vxa OUT.vxa] "
        "[--body-out BODY.json] [--experiment-out EXPERIMENT.json] [--mesh FILE.stl|FILE.obj] "
        "[--vtk DIR] [--replay REPLAY.bin [--time T]]",
        "Exports a body framed by its experiment (enclosure and overrides applied), or the\n"
        "champion of a run directory written by 'bhm evolve', as a VXA 1.0 file that\n"
        "VoxCAD opens, as a body JSON file, and/or the experiment as JSON; its outer surface\n"
        "as a closed triangle mesh (STL, or OBJ + MTL with one group per material), at rest or\n"
        "deformed at --time of --replay; a replay (or the body at rest) as a ParaView series\n"
        "(DIR/series.pvd, DIR/frame-NNNNN.vtu, DIR/com_path.vtp). Units are metres. Files are\n"
        "written atomically.");
    parser.positional("SOURCE", "an experiment file (with --body) or a run directory");
    parser.option("--body", "BODY.json", "the body to export (with an experiment file)");
    parser.option("--vxa", "OUT.vxa", "write a VoxCAD VXA 1.0 file", PathRole::OutputFile);
    parser.option("--body-out", "BODY.json", "write the (framed) body as a body file",
                  PathRole::OutputFile);
    parser.option("--experiment-out", "FILE.json", "write the experiment as a full experiment file",
                  PathRole::OutputFile);
    parser.option("--mesh", "FILE.stl|FILE.obj",
                  "write the outer surface (binary STL, or OBJ with FILE.mtl beside it)",
                  PathRole::OutputFile);
    parser.option("--vtk", "DIR", "write a ParaView time series (series.pvd + .vtu frames)",
                  PathRole::OutputDir);
    parser.option("--replay", "REPLAY.bin",
                  "a recorded simulation of the body: --mesh deformed, --vtk one frame each");
    parser.option("--time", "T", "replay time for --mesh (default: the last frame)");
    parser.option("--vtk-every", "K", "keep every K-th replay frame in --vtk (default 1)");
    return run_command(parser, args, run_export);
}

}  // namespace bhm::app
