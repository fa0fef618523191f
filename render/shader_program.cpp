#include "render/shader_program.hpp"

#include <glad/gl.h>

#include <cstdlib>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <vector>

#include <glm/gtc/type_ptr.hpp>

#include "engine/io/text_file.hpp"
#include "render/embedded_shaders.hpp"

namespace bhm::render {

namespace {

std::string info_log(GLuint object, bool is_program) {
    GLint length = 0;
    if (is_program)
        glGetProgramiv(object, GL_INFO_LOG_LENGTH, &length);
    else
        glGetShaderiv(object, GL_INFO_LOG_LENGTH, &length);
    std::vector<char> log(static_cast<std::size_t>(std::max(length, 1)), '\0');
    if (is_program)
        glGetProgramInfoLog(object, length, nullptr, log.data());
    else
        glGetShaderInfoLog(object, length, nullptr, log.data());
    std::string text(log.data());
    while (!text.empty() && (text.back() == '\n' || text.back() == '\0'))
        text.pop_back();
    return text;
}

GLuint compile(GLenum stage, const std::string& file_name) {
    const std::string source = shader_source(file_name);
    const GLuint shader = glCreateShader(stage);
    const char* text = source.c_str();
    glShaderSource(shader, 1, &text, nullptr);
    glCompileShader(shader);
    GLint ok = GL_FALSE;
    glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
    if (ok != GL_TRUE) {
        const std::string log = info_log(shader, false);
        glDeleteShader(shader);
        throw std::runtime_error("shaders/" + file_name + ": compile failed: " + log);
    }
    return shader;
}

}  // namespace

std::string shader_source(const std::string& file_name) {
    if (const char* dir = std::getenv("BHM_SHADER_DIR"); dir && *dir) {
        const std::string path = std::string(dir) + "/" + file_name;
        try {
            return engine::read_text(path, engine::kTextFileCap);
        } catch (const engine::FileReadError& e) {
            throw std::runtime_error(e.what() + std::string(" (BHM_SHADER_DIR is set)"));
        }
    }
    for (const auto& shader : embedded_shaders())
        if (file_name == shader.file_name) return shader.source;
    throw std::runtime_error("shaders/" + file_name + ": no such shader embedded in this build");
}

ShaderProgram::ShaderProgram(const std::string& vertex_file, const std::string& fragment_file,
                             const std::string& geometry_file)
    : label_(vertex_file + " + " + (geometry_file.empty() ? "" : geometry_file + " + ") +
             fragment_file) {
    std::vector<GLuint> stages;
    try {
        stages.push_back(compile(GL_VERTEX_SHADER, vertex_file));
        if (!geometry_file.empty()) stages.push_back(compile(GL_GEOMETRY_SHADER, geometry_file));
        stages.push_back(compile(GL_FRAGMENT_SHADER, fragment_file));
    } catch (...) {
        for (GLuint s : stages)
            glDeleteShader(s);
        throw;
    }
    program_ = glCreateProgram();
    for (GLuint s : stages)
        glAttachShader(program_, s);
    glLinkProgram(program_);
    for (GLuint s : stages)
        glDeleteShader(s);
    GLint ok = GL_FALSE;
    glGetProgramiv(program_, GL_LINK_STATUS, &ok);
    if (ok != GL_TRUE) {
        const std::string log = info_log(program_, true);
        glDeleteProgram(program_);
        program_ = 0;
        throw std::runtime_error("shaders/" + label_ + ": link failed: " + log);
    }
}

ShaderProgram::~ShaderProgram() {
    if (program_) glDeleteProgram(program_);
}

void ShaderProgram::use() const {
    glUseProgram(program_);
}

void ShaderProgram::set(const char* name, const glm::mat4& value) const {
    glUniformMatrix4fv(glGetUniformLocation(program_, name), 1, GL_FALSE, glm::value_ptr(value));
}
void ShaderProgram::set(const char* name, const glm::vec3& value) const {
    glUniform3fv(glGetUniformLocation(program_, name), 1, glm::value_ptr(value));
}
void ShaderProgram::set(const char* name, const glm::vec2& value) const {
    glUniform2fv(glGetUniformLocation(program_, name), 1, glm::value_ptr(value));
}
void ShaderProgram::set(const char* name, float value) const {
    glUniform1f(glGetUniformLocation(program_, name), value);
}

}  // namespace bhm::render
