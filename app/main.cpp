// bhm: BHM Studio's single executable. With no subcommand it opens the studio.
#include <cstring>
#include <iostream>
#include <string>
#include <vector>

#include "app/cli/commands.hpp"
#include "bhm_version.hpp"

namespace {

struct Subcommand {
    const char* name;
    int (*run)(const bhm::app::Args&);
    const char* summary;
};

constexpr Subcommand kSubcommands[] = {
    {"studio", bhm::app::cmd_studio, "open the BHM Studio desktop application (default)"},
    {"validate", bhm::app::cmd_validate, "check experiment and body files, report every problem"},
    {"materials", bhm::app::cmd_materials,
     "list the material library (values, ranges, sources)"},
    {"simulate", bhm::app::cmd_simulate, "simulate one body under an experiment"},
    {"evolve", bhm::app::cmd_evolve, "evolve morphologies headless (AFPO over CPPNs)"},
    {"render", bhm::app::cmd_render, "render a body or a replay to PNG without a display"},
    {"export", bhm::app::cmd_export,
     "export a body or a run's champion (VXA, body JSON, STL/OBJ mesh, VTK series)"},
    {"import", bhm::app::cmd_import, "read a VoxCAD/evosoro VXA file as experiment + body"},
    {"calibrate", bhm::app::cmd_calibrate, "fit simulation parameters to a measured track"},
    {"verify", bhm::app::cmd_verify,
     "check a body or a run's top designs in a continuum FEM (CalculiX)"},
    {"robustness", bhm::app::cmd_robustness,
     "a table and heatmap of bodies x controllers, each cell one evaluation"},
};

void print_usage(std::ostream& out) {
    out << "usage: bhm [SUBCOMMAND] [ARGS...]\n       bhm --version\n\nsubcommands:\n";
    for (const auto& s : kSubcommands)
        out << "  " << s.name << std::string(11 - std::strlen(s.name), ' ') << s.summary << "\n";
    out << "\n'bhm SUBCOMMAND --help' describes each one.\n";
}

}  // namespace

int main(int argc, char** argv) {
    std::vector<std::string> args(argv + 1, argv + argc);
    if (args.empty()) return bhm::app::cmd_studio({});
    const std::string first = args.front();
    if (first == "--version" || first == "-V") {
        std::cout << "bhm " << BHM_VERSION_STRING << "\n";
        return 0;
    }
    if (first == "--help" || first == "-h" || first == "help") {
        print_usage(std::cout);
        return 0;
    }
    for (const auto& s : kSubcommands) {
        if (first == s.name) return s.run(std::vector<std::string>(args.begin() + 1, args.end()));
    }
    if (!first.empty() && first[0] == '-') {
        // Options before any subcommand belong to the default one, the studio.
        return bhm::app::cmd_studio(args);
    }
    std::cerr << "bhm: unknown subcommand '" << first << "'\n";
    print_usage(std::cerr);
    return 2;
}
