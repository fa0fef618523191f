#pragma once
// Output paths checked before any work, so a typo or an unset shell variable (`--out ""`) costs
// nothing instead of a whole run that writes nowhere. Each check throws std::runtime_error with
// one line naming the option, the path and the reason (exit status 1); an empty path is a usage
// error (UsageError, exit status 2).
#include <string>

namespace bhm::app {

//! A file to be (re)placed: not empty, not a folder or a device, its folder exists and is writable.
void check_output_file(const std::string& option, const std::string& path);
//! A folder to be written into, created with its parents if missing: not empty, not a file, and
//! it (or its nearest existing ancestor, which must be a folder) is writable.
void check_output_dir(const std::string& option, const std::string& path);
//! A folder that must already exist and be writable (e.g. the run directory of --resume).
void check_existing_dir(const std::string& option, const std::string& path);

}  // namespace bhm::app
