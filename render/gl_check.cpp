#include "render/gl_check.hpp"

#include <glad/gl.h>

#include <stdexcept>

namespace bhm::render {

namespace {
std::string error_name(GLenum error) {
    switch (error) {
        case GL_INVALID_ENUM:
            return "GL_INVALID_ENUM";
        case GL_INVALID_VALUE:
            return "GL_INVALID_VALUE";
        case GL_INVALID_OPERATION:
            return "GL_INVALID_OPERATION";
        case GL_INVALID_FRAMEBUFFER_OPERATION:
            return "GL_INVALID_FRAMEBUFFER_OPERATION";
        case GL_OUT_OF_MEMORY:
            return "GL_OUT_OF_MEMORY";
        default:
            return "0x" + std::to_string(error);
    }
}
}  // namespace

void check_gl_error(const std::string& where) {
    std::string errors;
    // A lost context can report errors forever; a bounded drain keeps this from spinning.
    for (int i = 0; i < 16; ++i) {
        const GLenum error = glGetError();
        if (error == GL_NO_ERROR) break;
        errors += (errors.empty() ? "" : ", ") + error_name(error);
    }
    if (!errors.empty()) throw std::runtime_error("GL error " + errors + " after " + where);
}

}  // namespace bhm::render
