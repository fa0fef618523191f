#pragma once
// A small declarative command-line parser: each subcommand declares its options, the parser
// rejects anything else with a one-line error (exit code 2 is the caller's job).
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace bhm::app {

struct UsageError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

//! What an option's value is, for the checks made before the command starts (path_checks.hpp).
enum class PathRole {
    None,
    OutputFile,  //!< a file to write: its folder must exist and be writable
    OutputDir,   //!< a folder to write into (created if missing)
};

struct OptionSpec {
    std::string name;        //!< "--out"
    std::string value_name;  //!< "DIR"; empty for a flag
    std::string help;
    PathRole role = PathRole::None;
};

class ArgParser {
  public:
    ArgParser(std::string command, std::string synopsis, std::string summary);
    ArgParser& option(std::string name, std::string value_name, std::string help,
                      PathRole role = PathRole::None);
    ArgParser& flag(std::string name, std::string help);
    ArgParser& positional(std::string name, std::string help, bool repeated = false,
                          bool required = true);

    //! Parses args (after the subcommand). Throws UsageError on an unknown option, a missing
    //! value, or a missing positional. Returns false when --help was asked (usage printed).
    bool parse(const std::vector<std::string>& args);

    bool has(const std::string& name) const;
    std::string get(const std::string& name, const std::string& fallback = "") const;
    double get_double(const std::string& name, double fallback) const;
    long long get_int(const std::string& name, long long fallback) const;
    const std::vector<std::string>& positionals() const { return positionals_; }

    //! Checks every given output path (PathRole): UsageError for an empty one, std::runtime_error
    //! naming the option and the path for the rest. run_command calls it before the command.
    void check_paths() const;

    std::string usage() const;
    const std::string& command() const { return command_; }

  private:
    const OptionSpec* find(const std::string& name) const;
    std::string command_, synopsis_, summary_;
    std::vector<OptionSpec> options_;
    struct Positional {
        std::string name, help;
        bool repeated, required;
    };
    std::vector<Positional> positional_specs_;
    std::map<std::string, std::string> values_;
    std::vector<std::string> positionals_;
};

//! Runs a subcommand body once the arguments parse and the output paths pass check_paths(),
//! turning UsageError into "bhm CMD: message" + usage and exit 2, and any other exception into
//! "bhm CMD: message" and exit 1.
int run_command(ArgParser& parser, const std::vector<std::string>& args, int (*body)(ArgParser&));

}  // namespace bhm::app
