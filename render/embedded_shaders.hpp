#pragma once
// The GLSL sources of shaders/*, compiled into the binary (see render/embed_shaders.cmake).
#include <string>
#include <vector>

namespace bhm::render {

struct EmbeddedShader {
    const char* file_name;  //!< "box.vert"
    const char* source;
};

const std::vector<EmbeddedShader>& embedded_shaders();

}  // namespace bhm::render
