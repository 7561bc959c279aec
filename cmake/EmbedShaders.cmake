# Writes OUTPUT, a C++ file that defines `std::span<const hexlod::render::ShaderFile> SYMBOL()`
# over FILES (a ;-list of paths), each under its file name. Run by hexlod_embed_shaders with
# cmake -P so an edited shader regenerates the file at build time.
set(body "")
foreach(path IN LISTS FILES)
    get_filename_component(name "${path}" NAME)
    file(READ "${path}" text)
    string(APPEND body "    {\"${name}\", R\"hexlod_glsl(${text})hexlod_glsl\"},\n")
endforeach()
file(WRITE "${OUTPUT}.tmp" "// Generated from the shader sources by cmake/EmbedShaders.cmake; do not edit.
#include \"hexlod/render/shader_library.h\"

namespace {
const hexlod::render::ShaderFile kFiles[] = {
${body}};
} // namespace

std::span<const hexlod::render::ShaderFile> ${SYMBOL}() { return kFiles; }
")
# Only a changed file is rewritten, so unchanged shaders do not trigger a rebuild.
file(COPY_FILE "${OUTPUT}.tmp" "${OUTPUT}" ONLY_IF_DIFFERENT)
file(REMOVE "${OUTPUT}.tmp")
