// bhm validate FILE...: checks experiment and body files and reports every problem, one per line.
#include <iostream>
#include <optional>

#include "app/cli/arg_parser.hpp"
#include "app/cli/commands.hpp"
#include "app/cli/file_kind.hpp"
#include "app/cli/problem_report.hpp"
#include "evo/experiment/experiment_io.hpp"
#include "evo/experiment/validated_envelope.hpp"

namespace bhm::app {

namespace {

int validate_body(ArgParser& parser) {
    std::vector<evo::Problem> problems;
    std::optional<evo::Experiment> experiment;
    std::vector<std::string> bodies;
    // Outside the validated envelope (docs/physics.md): reported, not refused.
    std::vector<evo::Problem> warnings;
    for (const auto& path : parser.positionals()) {
        try {
            if (detect_file_kind(path) == FileKind::Body) {
                bodies.push_back(path);
                evo::load_body(path);
            } else {
                auto e = evo::load_experiment(path);
                say_library_warnings(e);
                if (!experiment) experiment = e;
                auto more = evo::envelope_warnings(e, nullptr, path);
                warnings.insert(warnings.end(), more.begin(), more.end());
            }
        } catch (const evo::ValidationError& error) {
            problems.insert(problems.end(), error.problems.begin(), error.problems.end());
        }
    }
    // Bodies are checked against the first valid experiment named in the same call.
    if (experiment) {
        for (const auto& path : bodies) {
            try {
                auto body = evo::load_body(path);
                auto more = evo::validate_body_against(body, *experiment, path);
                problems.insert(problems.end(), more.begin(), more.end());
                if (more.empty()) {
                    auto w = evo::envelope_warnings(*experiment, &body, path);
                    warnings.insert(warnings.end(), w.begin(), w.end());
                }
            } catch (const evo::ValidationError&) {
                // already reported above
            }
        }
    }
    print_problems(problems);
    if (!parser.has("--quiet")) print_problems(warnings);  // file:field: warning: ...
    if (!problems.empty()) return 1;
    if (!parser.has("--quiet")) std::cout << parser.positionals().size() << " file(s) valid\n";
    return 0;
}

}  // namespace

int cmd_validate(const Args& args) {
    ArgParser parser(
        "validate", "FILE... [--quiet]",
        "Checks experiment and body files and reports every problem, one per line, as\n"
        "file:field: message. A body file is recognised by its \"layers\" key; bodies are\n"
        "also checked against the first experiment named in the same call.\n"
        "Materials outside the envelope docs/physics.md validates (stiffness contrast, Poisson's\n"
        "ratio) are reported as file:field: warning: ..., which does not fail.\n"
        "Exit status: 0 when every file is valid, 1 when not, 2 on a usage error.");
    parser.positional("FILE", "experiment (.json) or body (.json) file", true, true);
    parser.flag("--quiet", "print nothing when valid (no warnings either)");
    return run_command(parser, args, validate_body);
}

}  // namespace bhm::app
