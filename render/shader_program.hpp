#pragma once
// A linked GLSL program built from files of shaders/ (embedded in the binary). Compile and link
// errors throw std::runtime_error with the file names and the driver's log.
#include <string>

#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

namespace bhm::render {

//! The source of one shader file, e.g. "box.vert". When the environment variable
//! BHM_SHADER_DIR names a folder, the file is read from there instead (live shader editing).
//! Throws std::runtime_error for an unknown name or an unreadable file.
std::string shader_source(const std::string& file_name);

class ShaderProgram {
  public:
    //! geometry_file may be empty. Needs a current GL context.
    ShaderProgram(const std::string& vertex_file, const std::string& fragment_file,
                  const std::string& geometry_file = "");
    ~ShaderProgram();
    ShaderProgram(const ShaderProgram&) = delete;
    ShaderProgram& operator=(const ShaderProgram&) = delete;

    void use() const;
    unsigned id() const { return program_; }
    //! Setters on the program in use; a uniform the compiler removed is silently skipped.
    void set(const char* name, const glm::mat4& value) const;
    void set(const char* name, const glm::vec3& value) const;
    void set(const char* name, const glm::vec2& value) const;
    void set(const char* name, float value) const;

  private:
    unsigned program_ = 0;
    std::string label_;
};

}  // namespace bhm::render
