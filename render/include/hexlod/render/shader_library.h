// GLSL sources by name, with `#include "name"` resolved and errors mapped back to file:line.
// Modules embed their shaders at build time (hexlod_embed_shaders in CMake) so a binary never
// depends on where it was built; HEXLOD_SHADER_DIR, when set, reads them from that folder
// instead, to iterate on a shader without rebuilding.
#pragma once

#include <span>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

namespace hexlod::render {

struct ShaderFile {
    std::string_view name; // e.g. "terminal.vert", "gpu_types.h"
    std::string_view text;
};

// The expanded source of one stage: `sourceNames[i]` is the file behind GLSL source string
// number i, as set by the #line directives the expansion inserts.
struct ExpandedShader {
    std::string text;
    std::vector<std::string> sourceNames;
};

class ShaderLibrary {
public:
    void add(std::span<const ShaderFile> files); // later files replace earlier ones of the same name
    void add(std::string name, std::string text);
    bool contains(std::string_view name) const;

    // Expands `name`: `defines` (lines such as "#define LOD 3") go right after its #version
    // line; each #include "x" is replaced by x's expansion, once per stage (later includes of the
    // same file are dropped, like #pragma once). False with "file:line: message" for a
    // missing file or include, an include cycle or a missing #version.
    bool expand(std::string_view name, std::string_view defines, ExpandedShader& out,
                std::string& error) const;

    // Rewrites a driver's info log ("0:12(5): error: ..." from Mesa, "0(12) : error ..." from
    // NVIDIA) into "file:line: error: ..." using the expansion's source names.
    static std::string mapLog(std::string_view log, const ExpandedShader& shader);

private:
    bool expandInto(const std::string& name, int depth, ExpandedShader& out, std::string& error) const;
    const std::string* text(std::string_view name) const;

    std::unordered_map<std::string, std::string> files_;
};

} // namespace hexlod::render
