#pragma once
// GL error checks that name the step that failed. Needs a current context with glad loaded.
#include <string>

namespace bhm::render {

//! Throws std::runtime_error "GL error GL_INVALID_OPERATION after <where>" when glGetError
//! reports anything (all pending errors are drained and listed).
void check_gl_error(const std::string& where);

}  // namespace bhm::render
