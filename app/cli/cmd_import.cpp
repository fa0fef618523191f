// bhm import: a VoxCAD / evosoro VXA (or VXC) file as an experiment file and a body file. The
// mapping lives in evo/formats/vxa_import.hpp; this file wires it to the command line.
#include <iostream>

#include "app/cli/arg_parser.hpp"
#include "app/cli/commands.hpp"
#include "app/cli/problem_report.hpp"
#include "evo/experiment/experiment_io.hpp"
#include "evo/formats/vxa_import.hpp"

namespace bhm::app {

namespace {

int import_vxa(ArgParser& parser) {
    const std::string source = parser.positionals().front();
    if (!parser.has("--experiment-out") && !parser.has("--body-out"))
        throw UsageError("nothing to write: give --experiment-out and/or --body-out");
    const evo::VxaImport imported = evo::load_vxa(source);  // throws naming the file and field
    for (const auto& line : imported.unmapped)
        std::cerr << source << ": not mapped: " << line << "\n";
    // What we write must load again: check before writing anything.
    auto problems = evo::validate_experiment(imported.experiment, source);
    const auto body_problems =
        evo::validate_body_against(imported.body, imported.experiment, source);
    problems.insert(problems.end(), body_problems.begin(), body_problems.end());
    if (!problems.empty()) {
        print_problems(problems);
        std::cerr << "bhm import: " << source
                  << " maps to an experiment BHM cannot simulate; nothing written\n";
        return 1;
    }
    if (parser.has("--experiment-out")) {
        evo::save_experiment(parser.get("--experiment-out"), imported.experiment);
        std::cout << "wrote " << parser.get("--experiment-out") << "\n";
    }
    if (parser.has("--body-out")) {
        evo::save_body(parser.get("--body-out"), imported.body);
        std::cout << "wrote " << parser.get("--body-out") << "\n";
    }
    int voxels = 0;
    for (auto c : imported.body.cells)
        voxels += c ? 1 : 0;
    std::cout << source << ": " << imported.body.size[0] << "x" << imported.body.size[1] << "x"
              << imported.body.size[2] << " lattice, " << voxels << " voxels, "
              << imported.experiment.materials.size() << " materials"
              << (imported.had_bhm_experiment ? ", written by BHM: read back exactly" : "") << "; "
              << imported.unmapped.size() << " setting(s) not mapped\n";
    return 0;
}

}  // namespace

int cmd_import(const Args& args) {
    ArgParser parser(
        "import", "FILE.vxa [--experiment-out EXPERIMENT.json] [--body-out BODY.json]",
        "Reads a VXA (or VXC) file as VoxCAD and evosoro (Kriegman et al.) write it: palette,\n"
        "ASCII_READABLE structure layers, lattice size, damping, gravity and floor, thermal\n"
        "actuation, stop time and fully fixed box regions (as fixed faces or fixed voxels).\n"
        "Every setting it cannot map is printed on stderr as 'FILE: not mapped: ...'. A file\n"
        "written by 'bhm export --vxa' reads back exactly. Files are written atomically, and\n"
        "only when the result validates.\n"
        "\n"
        "exit status: 0 ok, 1 unreadable file or an experiment BHM cannot simulate, 2 usage.");
    parser.positional("FILE.vxa", "the VoxCAD file");
    parser.option("--experiment-out", "EXPERIMENT.json", "write the experiment file",
                  PathRole::OutputFile);
    parser.option("--body-out", "BODY.json", "write the body file (workspace-sized)",
                  PathRole::OutputFile);
    return run_command(parser, args, import_vxa);
}

}  // namespace bhm::app
