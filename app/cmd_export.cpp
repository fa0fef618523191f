// bhm export: a body, or a run's champion, as a VoxCAD VXA file, a body JSON or an experiment JSON.
#include <filesystem>
#include <fstream>
#include <iostream>

#include "app/arg_parser.hpp"
#include "app/commands.hpp"
#include "app/run_directory.hpp"
#include "evo/experiment_io.hpp"
#include "evo/scene.hpp"
#include "evo/vxa.hpp"

namespace bhm::app {

namespace {

int export_body(ArgParser& parser) {
    namespace fs = std::filesystem;
    const std::string source = parser.positionals().front();
    evo::Experiment experiment;
    evo::Body body;
    if (fs::is_directory(source)) {
        if (parser.has("--body"))
            throw UsageError("--body is for an experiment file; a run directory has its champion");
        auto run = load_run_champion(source);
        experiment = run.experiment;
        body = run.body;
    } else {
        if (!parser.has("--body")) throw UsageError("an experiment file needs --body BODY.json");
        experiment = evo::load_experiment(source);
        body = evo::load_body(parser.get("--body"));
        auto problems = evo::validate_body_against(body, experiment, parser.get("--body"));
        if (!problems.empty()) throw evo::ValidationError(problems);
        body = evo::apply_frame_and_overrides(experiment, body);
    }
    if (!parser.has("--vxa") && !parser.has("--body-out") && !parser.has("--experiment-out"))
        throw UsageError("nothing to write: give --vxa, --body-out and/or --experiment-out");
    if (parser.has("--vxa")) {
        evo::save_vxa(parser.get("--vxa"), experiment, body);
        std::cout << "wrote " << parser.get("--vxa") << "\n";
    }
    if (parser.has("--body-out")) {
        evo::save_body(parser.get("--body-out"), body);
        std::cout << "wrote " << parser.get("--body-out") << "\n";
    }
    if (parser.has("--experiment-out")) {
        evo::save_experiment(parser.get("--experiment-out"), experiment);
        std::cout << "wrote " << parser.get("--experiment-out") << "\n";
    }
    return 0;
}

int run_export(ArgParser& parser) {
    try {
        return export_body(parser);
    } catch (const evo::ValidationError& e) {
        for (const auto& p : e.problems)
            std::cerr << p.to_string() << "\n";
        return 1;
    }
}

}  // namespace

int cmd_export(const Args& args) {
    ArgParser parser(
        "export",
        "(EXPERIMENT.json --body BODY.json | RUN_DIR) [--vxa OUT.vxa] "
        "[--body-out BODY.json] [--experiment-out EXPERIMENT.json]",
        "Exports a body framed by its experiment (enclosure and overrides applied), or the\n"
        "champion of a run directory written by 'bhm evolve', as a VXA 1.0 file that\n"
        "VoxCAD opens, as a body JSON file, and/or the experiment as JSON. Files are\n"
        "written atomically.");
    parser.positional("SOURCE", "an experiment file (with --body) or a run directory");
    parser.option("--body", "BODY.json", "the body to export (with an experiment file)");
    parser.option("--vxa", "OUT.vxa", "write a VoxCAD VXA 1.0 file");
    parser.option("--body-out", "BODY.json", "write the (framed) body as a body file");
    parser.option("--experiment-out", "FILE.json",
                  "write the experiment as a full experiment file");
    return run_command(parser, args, run_export);
}

}  // namespace bhm::app
