// Compiling and linking GL programs with their errors mapped to file:line.
#include "hexlod/render/shader_program.h"
#include "hexlod/render/gl_api.h"

#include <glm/gtc/type_ptr.hpp>

#include <vector>

namespace hexlod::render {
namespace {

GLenum glStage(ShaderStage stage) {
    switch (stage) {
    case ShaderStage::Vertex:
        return GL_VERTEX_SHADER;
    case ShaderStage::Fragment:
        return GL_FRAGMENT_SHADER;
    case ShaderStage::Compute:
        return GL_COMPUTE_SHADER;
    }
    return GL_VERTEX_SHADER;
}

std::string shaderLog(GLuint shader) {
    GLint length = 0;
    gl::glGetShaderiv(shader, GL_INFO_LOG_LENGTH, &length);
    std::string log(size_t(std::max(length, 1)), '\0');
    gl::glGetShaderInfoLog(shader, length, nullptr, log.data());
    log.resize(log.find('\0') == std::string::npos ? log.size() : log.find('\0'));
    return log;
}

std::string programLog(GLuint program) {
    GLint length = 0;
    gl::glGetProgramiv(program, GL_INFO_LOG_LENGTH, &length);
    std::string log(size_t(std::max(length, 1)), '\0');
    gl::glGetProgramInfoLog(program, length, nullptr, log.data());
    log.resize(log.find('\0') == std::string::npos ? log.size() : log.find('\0'));
    return log;
}

} // namespace

ShaderProgram::~ShaderProgram() {
    if (id_) gl::glDeleteProgram(id_);
}

ShaderProgram& ShaderProgram::operator=(ShaderProgram&& other) noexcept {
    if (this != &other) {
        if (id_) gl::glDeleteProgram(id_);
        id_ = std::exchange(other.id_, 0);
    }
    return *this;
}

ShaderProgram ShaderProgram::build(const ShaderLibrary& library,
                                   std::initializer_list<ShaderStageSource> stages, std::string_view defines,
                                   std::string& error) {
    error.clear();
    std::vector<GLuint> shaders;
    auto cleanup = [&shaders] {
        for (GLuint shader : shaders) gl::glDeleteShader(shader);
    };
    std::string names;
    for (const ShaderStageSource& stage : stages) {
        ExpandedShader expanded;
        if (!library.expand(stage.name, defines, expanded, error)) {
            cleanup();
            return {};
        }
        GLuint shader = gl::glCreateShader(glStage(stage.stage));
        shaders.push_back(shader);
        const char* text = expanded.text.c_str();
        gl::glShaderSource(shader, 1, &text, nullptr);
        gl::glCompileShader(shader);
        GLint compiled = GL_FALSE;
        gl::glGetShaderiv(shader, GL_COMPILE_STATUS, &compiled);
        if (!compiled) error += ShaderLibrary::mapLog(shaderLog(shader), expanded);
        names += (names.empty() ? "" : " + ") + std::string(stage.name);
    }
    if (!error.empty()) {
        cleanup();
        return {};
    }
    GLuint program = gl::glCreateProgram();
    for (GLuint shader : shaders) gl::glAttachShader(program, shader);
    gl::glLinkProgram(program);
    for (GLuint shader : shaders) gl::glDetachShader(program, shader);
    cleanup();
    GLint linked = GL_FALSE;
    gl::glGetProgramiv(program, GL_LINK_STATUS, &linked);
    if (!linked) {
        error = names + ": link error: " + programLog(program);
        gl::glDeleteProgram(program);
        return {};
    }
    return ShaderProgram(program);
}

void ShaderProgram::use() const {
    gl::glUseProgram(id_);
}

void ShaderProgram::set(const char* name, int value) const {
    gl::glProgramUniform1i(id_, gl::glGetUniformLocation(id_, name), value);
}
void ShaderProgram::set(const char* name, uint32_t value) const {
    gl::glProgramUniform1ui(id_, gl::glGetUniformLocation(id_, name), value);
}
void ShaderProgram::set(const char* name, float value) const {
    gl::glProgramUniform1f(id_, gl::glGetUniformLocation(id_, name), value);
}
void ShaderProgram::set(const char* name, const glm::vec2& value) const {
    gl::glProgramUniform2f(id_, gl::glGetUniformLocation(id_, name), value.x, value.y);
}
void ShaderProgram::set(const char* name, const glm::vec3& value) const {
    gl::glProgramUniform3f(id_, gl::glGetUniformLocation(id_, name), value.x, value.y, value.z);
}
void ShaderProgram::set(const char* name, const glm::vec4& value) const {
    gl::glProgramUniform4fv(id_, gl::glGetUniformLocation(id_, name), 1, glm::value_ptr(value));
}
void ShaderProgram::set(const char* name, const glm::uvec4& value) const {
    gl::glProgramUniform4ui(id_, gl::glGetUniformLocation(id_, name), value.x, value.y, value.z, value.w);
}
void ShaderProgram::set(const char* name, const glm::mat4& value) const {
    gl::glProgramUniformMatrix4fv(id_, gl::glGetUniformLocation(id_, name), 1, GL_FALSE,
                                  glm::value_ptr(value));
}

} // namespace hexlod::render
