#pragma once
// One function per subcommand; each lives in its own cmd_*.cpp and returns the exit code
// (0 ok, 1 failure or invalid input, 2 usage error).
#include <string>
#include <vector>

namespace bhm::app {

using Args = std::vector<std::string>;
int cmd_studio(const Args& args);
int cmd_validate(const Args& args);
int cmd_materials(const Args& args);
int cmd_simulate(const Args& args);
int cmd_evolve(const Args& args);
int cmd_render(const Args& args);
int cmd_export(const Args& args);
int cmd_import(const Args& args);
int cmd_verify(const Args& args);
int cmd_calibrate(const Args& args);
int cmd_robustness(const Args& args);

}  // namespace bhm::app
