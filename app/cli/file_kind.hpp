#pragma once
#include <string>

namespace bhm::app {

enum class FileKind { Experiment, Body };

//! A JSON object with a "layers" key is a body file; anything else is read as an experiment
//! (whose loader then reports what is wrong with it).
FileKind detect_file_kind(const std::string& path);

}  // namespace bhm::app
