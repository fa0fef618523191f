#include "app/cli/arg_parser.hpp"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <sstream>

#include "app/cli/path_checks.hpp"
#include "evo/experiment/json_reader.hpp"

namespace bhm::app {

ArgParser::ArgParser(std::string command, std::string synopsis, std::string summary)
    : command_(std::move(command)), synopsis_(std::move(synopsis)), summary_(std::move(summary)) {
    flag("--help", "show this help and exit");
}

ArgParser& ArgParser::option(std::string name, std::string value_name, std::string help,
                             PathRole role) {
    options_.push_back({std::move(name), std::move(value_name), std::move(help), role});
    return *this;
}

void ArgParser::check_paths() const {
    for (const auto& o : options_) {
        const auto it = values_.find(o.name);
        if (it == values_.end()) continue;
        if (o.role == PathRole::OutputFile) check_output_file(o.name, it->second);
        if (o.role == PathRole::OutputDir) check_output_dir(o.name, it->second);
    }
}

ArgParser& ArgParser::flag(std::string name, std::string help) {
    options_.push_back({std::move(name), "", std::move(help)});
    return *this;
}

ArgParser& ArgParser::positional(std::string name, std::string help, bool repeated, bool required) {
    positional_specs_.push_back({std::move(name), std::move(help), repeated, required});
    return *this;
}

const OptionSpec* ArgParser::find(const std::string& name) const {
    for (const auto& o : options_)
        if (o.name == name) return &o;
    return nullptr;
}

bool ArgParser::parse(const std::vector<std::string>& args) {
    for (size_t i = 0; i < args.size(); ++i) {
        std::string arg = args[i];
        if (arg.size() > 1 && arg[0] == '-' && arg != "-") {
            std::string value;
            bool inline_value = false;
            if (auto eq = arg.find('='); eq != std::string::npos && arg.rfind("--", 0) == 0) {
                value = arg.substr(eq + 1);
                arg = arg.substr(0, eq);
                inline_value = true;
            }
            if (arg == "-h") arg = "--help";
            const OptionSpec* spec = find(arg);
            if (!spec) throw UsageError("unknown option '" + arg + "'");
            if (spec->value_name.empty()) {
                if (inline_value) throw UsageError("option '" + arg + "' takes no value");
                values_[arg] = "1";
            } else if (inline_value) {
                values_[arg] = value;
            } else {
                if (i + 1 >= args.size())
                    throw UsageError("option '" + arg + "' needs a value " + spec->value_name);
                values_[arg] = args[++i];
            }
            if (arg == "--help") {
                std::cout << usage();
                return false;
            }
        } else {
            positionals_.push_back(arg);
        }
    }
    size_t required = 0;
    bool repeated = false;
    for (const auto& p : positional_specs_) {
        if (p.required) ++required;
        repeated = repeated || p.repeated;
    }
    if (positionals_.size() < required) {
        const auto& missing = positional_specs_[positionals_.size()];
        throw UsageError("missing " + missing.name);
    }
    if (!repeated && positionals_.size() > positional_specs_.size())
        throw UsageError("unexpected argument '" + positionals_[positional_specs_.size()] + "'");
    return true;
}

bool ArgParser::has(const std::string& name) const {
    return values_.count(name) != 0;
}

std::string ArgParser::get(const std::string& name, const std::string& fallback) const {
    auto it = values_.find(name);
    return it == values_.end() ? fallback : it->second;
}

double ArgParser::get_double(const std::string& name, double fallback) const {
    auto it = values_.find(name);
    if (it == values_.end()) return fallback;
    char* end = nullptr;
    errno = 0;
    double v = std::strtod(it->second.c_str(), &end);
    if (end == it->second.c_str() || *end != '\0' || errno != 0 || !std::isfinite(v))
        throw UsageError("option '" + name + "' needs a number, got '" + it->second + "'");
    return v;
}

long long ArgParser::get_int(const std::string& name, long long fallback) const {
    auto it = values_.find(name);
    if (it == values_.end()) return fallback;
    char* end = nullptr;
    errno = 0;
    long long v = std::strtoll(it->second.c_str(), &end, 10);
    if (end == it->second.c_str() || *end != '\0' || errno != 0)
        throw UsageError("option '" + name + "' needs an integer, got '" + it->second + "'");
    return v;
}

std::string ArgParser::usage() const {
    std::ostringstream out;
    out << "usage: bhm " << command_ << " " << synopsis_ << "\n\n" << summary_ << "\n";
    if (!positional_specs_.empty()) {
        out << "\narguments:\n";
        for (const auto& p : positional_specs_)
            out << "  " << p.name << "\n      " << p.help << "\n";
    }
    out << "\noptions:\n";
    for (const auto& o : options_) {
        out << "  " << o.name;
        if (!o.value_name.empty()) out << " " << o.value_name;
        out << "\n      " << o.help << "\n";
    }
    return out.str();
}

int run_command(ArgParser& parser, const std::vector<std::string>& args, int (*body)(ArgParser&)) {
    try {
        if (!parser.parse(args)) return 0;
        parser.check_paths();
        return body(parser);
    } catch (const UsageError& e) {
        std::cerr << "bhm " << parser.command() << ": " << e.what() << "\n"
                  << "usage: bhm " << parser.command() << " --help\n";
        return 2;
    } catch (const std::exception& e) {
        // The last line of defence: a library's internal tags never reach the user.
        std::cerr << "bhm " << parser.command() << ": " << evo::without_json_tags(e.what()) << "\n";
        return 1;
    }
}

}  // namespace bhm::app
