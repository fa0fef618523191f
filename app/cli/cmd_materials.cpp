// bhm materials [FILTER]: lists the material library (docs/materials-format.md) with each value,
// the range reported and its source; a broken library file is reported like `bhm validate` does.
#include <algorithm>
#include <cctype>
#include <iostream>

#include "app/cli/arg_parser.hpp"
#include "app/cli/commands.hpp"
#include "app/cli/problem_report.hpp"
#include "evo/experiment/material_library.hpp"

namespace bhm::app {

namespace {

std::string lower(std::string s) {
    for (auto& c : s)
        c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return s;
}

int list_materials(ArgParser& parser) {
    const std::string dir = parser.get("--dir", evo::default_material_library_dir());
    evo::MaterialLibrary library;
    try {
        library = evo::load_material_library(dir);
    } catch (const evo::ValidationError& e) {
        return report_problems(e.problems);
    }
    // What was not read, on stderr before the list (issue 41 R10): a skipped folder, FIFO or
    // dangling link is a warning; a damaged file is every problem of it, and exit 1 after the
    // materials that did read are listed.
    for (const auto& p : library.skipped)
        std::cerr << "bhm materials: warning: " << p.to_string() << "\n";
    for (const auto& d : library.damaged)
        print_problems(d.problems);
    const std::string filter =
        parser.positionals().empty() ? std::string() : lower(parser.positionals().front());
    int shown = 0;
    for (const auto& m : library.materials) {
        const std::string haystack = lower(m.id + " " + m.name + " " + m.category);
        if (!filter.empty() && haystack.find(filter) == std::string::npos) continue;
        std::cout << m.id << "  " << m.name << "  (" << m.category
                  << (m.active ? ", active" : "") << ")\n"
                  << evo::describe_library_material(m) << "\n";
        ++shown;
    }
    std::cout << shown << " of " << library.materials.size() << " material(s) in " << library.dir
              << "\n";
    if (!library.damaged.empty()) {
        std::cerr << "bhm materials: " << library.damaged.size()
                  << " damaged file(s) left out; experiments naming them fail\n";
        return 1;
    }
    return 0;
}

}  // namespace

int cmd_materials(const Args& args) {
    ArgParser parser(
        "materials", "[FILTER] [--dir DIR]",
        "Lists the material library: for each material its id (what an experiment's\n"
        "\"library\" key names), E, Poisson's ratio, density and, for active tissue, the\n"
        "contraction strain and frequency, each with the range reported and its source.\n"
        "FILTER keeps the materials whose id, name or category contains it.\n"
        "Entries that are not files (folders, FIFOs, dangling links) are named on stderr\n"
        "and skipped; an invalid file's problems are printed and the rest is listed.\n"
        "Exit status: 0, 1 when a library file is invalid, 2 on a usage error.");
    parser.positional("FILTER", "part of an id, name or category", false, false);
    parser.option("--dir", "DIR",
                  "the library folder (default: $BHM_MATERIALS_DIR, else the shipped one)");
    return run_command(parser, args, list_materials);
}

}  // namespace bhm::app
