// Impostor atlases on the GPU: every shape of one layout as a layer of two RGBA16F texture
// arrays (albedo, normal-depth), with the layout's direction table beside them. Needs a
// current GL context; owns its textures.
#pragma once

#include "hexlod/impostor/impostor_atlas.h"
#include "hexlod/impostor/view_lookup.h"
#include "hexlod/render/shader_program.h"

#include <span>
#include <string>

namespace hexlod::impostor {

class ImpostorTextures {
public:
    ImpostorTextures() = default;
    ~ImpostorTextures();
    ImpostorTextures(const ImpostorTextures&) = delete;
    ImpostorTextures& operator=(const ImpostorTextures&) = delete;

    // Uploads the atlases (all of `layout`; their index is their layer) and `table`. False with
    // a reason when an atlas has another layout or the arrays exceed the GL's limits.
    bool upload(const ViewLayout& layout, std::span<const ImpostorAtlas* const> atlases,
                const DirectionTable& table, std::string& error);

    // Binds the four textures to units base..base+3 and sets the uniforms impostor_views.glsl
    // declares on `program`.
    void bind(const render::ShaderProgram& program, uint32_t baseUnit) const;

    const ViewLayout& layout() const { return layout_; }
    uint32_t layers() const { return layers_; }
    uint64_t byteSize() const { return bytes_; } // GPU memory of the four textures

private:
    void release();

    ViewLayout layout_;
    uint32_t layers_ = 0;
    uint64_t bytes_ = 0;
    uint32_t albedo_ = 0, normalDepth_ = 0, tableViews_ = 0, tableWeights_ = 0;
};

// The impostor module's embedded GLSL (impostor/shaders/), on top of render's.
render::ShaderLibrary impostorShaderLibrary();

} // namespace hexlod::impostor
