// A linked GL program built from a ShaderLibrary, owning its GL object.
#pragma once

#include "hexlod/render/shader_library.h"

#include <glm/glm.hpp>

#include <cstdint>
#include <initializer_list>
#include <string>
#include <string_view>
#include <utility>

namespace hexlod::render {

enum class ShaderStage : uint8_t { Vertex, Fragment, Compute };

struct ShaderStageSource {
    ShaderStage stage;
    std::string_view name; // in the library
};

class ShaderProgram {
public:
    ShaderProgram() = default;
    ~ShaderProgram();
    ShaderProgram(ShaderProgram&& other) noexcept : id_(std::exchange(other.id_, 0)) {}
    ShaderProgram& operator=(ShaderProgram&& other) noexcept;
    ShaderProgram(const ShaderProgram&) = delete;
    ShaderProgram& operator=(const ShaderProgram&) = delete;

    // Compiles and links; on failure returns an empty program and sets `error` to every
    // message as "file:line: error: ...", the file being the shader or header at fault.
    static ShaderProgram build(const ShaderLibrary& library, std::initializer_list<ShaderStageSource> stages,
                               std::string_view defines, std::string& error);

    bool valid() const { return id_ != 0; }
    uint32_t id() const { return id_; }
    void use() const;

    // Uniform setters by name; a name the linker optimised away is ignored, as GL does.
    void set(const char* name, int value) const;
    void set(const char* name, uint32_t value) const;
    void set(const char* name, float value) const;
    void set(const char* name, const glm::vec2& value) const;
    void set(const char* name, const glm::vec3& value) const;
    void set(const char* name, const glm::vec4& value) const;
    void set(const char* name, const glm::uvec4& value) const;
    void set(const char* name, const glm::mat4& value) const;

private:
    explicit ShaderProgram(uint32_t id) : id_(id) {}
    uint32_t id_ = 0;
};

} // namespace hexlod::render
