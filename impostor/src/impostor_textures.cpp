// Uploading impostor atlases and direction tables.
#include "hexlod/impostor/impostor_textures.h"
#include "hexlod/render/gl_api.h"
#include "hexlod/render/render_shaders.h"

#include <Imath/half.h>

#include <vector>

std::span<const hexlod::render::ShaderFile> hexlodImpostorShaders();

namespace hexlod::impostor {

render::ShaderLibrary impostorShaderLibrary() {
    render::ShaderLibrary library = render::renderShaderLibrary();
    library.add(hexlodImpostorShaders());
    return library;
}

ImpostorTextures::~ImpostorTextures() {
    release();
}

void ImpostorTextures::release() {
    uint32_t textures[4] = {albedo_, normalDepth_, tableViews_, tableWeights_};
    for (uint32_t texture : textures)
        if (texture) gl::glDeleteTextures(1, &texture);
    albedo_ = normalDepth_ = tableViews_ = tableWeights_ = 0;
    layers_ = 0;
    bytes_ = 0;
}

bool ImpostorTextures::upload(const ViewLayout& layout, std::span<const ImpostorAtlas* const> atlases,
                              const DirectionTable& table, std::string& error) {
    release();
    if (!layout.validate(error)) return false;
    GLint maxLayers = 0, maxSize = 0;
    gl::glGetIntegerv(GL_MAX_ARRAY_TEXTURE_LAYERS, &maxLayers);
    gl::glGetIntegerv(GL_MAX_TEXTURE_SIZE, &maxSize);
    const uint32_t size = layout.atlasSize();
    const uint32_t layers = uint32_t(std::max<size_t>(atlases.size(), 1));
    if (layers > uint32_t(maxLayers) || size > uint32_t(maxSize)) {
        error = std::to_string(layers) + " impostor layers of " + std::to_string(size) +
                "^2 exceed the GL's limits (" + std::to_string(maxLayers) + " layers of " +
                std::to_string(maxSize) + "^2)";
        return false;
    }
    for (const ImpostorAtlas* atlas : atlases) {
        const ViewLayout& other = atlas->layout;
        if (other.sphere != layout.sphere || other.grid != layout.grid ||
            other.viewResolution != layout.viewResolution || other.padding != layout.padding) {
            error = "impostor '" + atlas->shape + "' was baked with another layout";
            return false;
        }
    }
    layout_ = layout;
    layers_ = uint32_t(atlases.size());
    auto makeArray = [&](uint32_t& texture) {
        gl::glCreateTextures(GL_TEXTURE_2D_ARRAY, 1, &texture);
        gl::glTextureStorage3D(texture, 1, GL_RGBA16F, GLsizei(size), GLsizei(size), GLsizei(layers));
        gl::glTextureParameteri(texture, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
        gl::glTextureParameteri(texture, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
        gl::glTextureParameteri(texture, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
        gl::glTextureParameteri(texture, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    };
    makeArray(albedo_);
    makeArray(normalDepth_);
    std::vector<half> texels(size_t(size) * size * 4);
    for (uint32_t layer = 0; layer < atlases.size(); ++layer) {
        for (auto [texture, image] : {std::pair{albedo_, &atlases[layer]->albedo},
                                      std::pair{normalDepth_, &atlases[layer]->normalDepth}}) {
            for (size_t i = 0; i < texels.size(); ++i) texels[i] = half(image->pixels[i]);
            gl::glTextureSubImage3D(texture, 0, 0, 0, GLint(layer), GLsizei(size), GLsizei(size), 1, GL_RGBA,
                                    GL_HALF_FLOAT, texels.data());
        }
    }
    bytes_ = uint64_t(size) * size * layers * 16;

    const GLsizei n = GLsizei(table.resolution);
    std::vector<uint32_t> views(table.texels.size() * 4);
    std::vector<float> weights(table.texels.size() * 4);
    for (size_t t = 0; t < table.texels.size(); ++t) {
        for (int i = 0; i < 4; ++i) {
            views[t * 4 + i] = table.texels[t].views[i];
            weights[t * 4 + i] = table.texels[t].weights[i];
        }
    }
    gl::glCreateTextures(GL_TEXTURE_2D, 1, &tableViews_);
    gl::glTextureStorage2D(tableViews_, 1, GL_RGBA32UI, n, n);
    gl::glTextureSubImage2D(tableViews_, 0, 0, 0, n, n, GL_RGBA_INTEGER, GL_UNSIGNED_INT, views.data());
    gl::glCreateTextures(GL_TEXTURE_2D, 1, &tableWeights_);
    gl::glTextureStorage2D(tableWeights_, 1, GL_RGBA32F, n, n);
    gl::glTextureSubImage2D(tableWeights_, 0, 0, 0, n, n, GL_RGBA, GL_FLOAT, weights.data());
    for (uint32_t texture : {tableViews_, tableWeights_}) {
        gl::glTextureParameteri(texture, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        gl::glTextureParameteri(texture, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    }
    bytes_ += uint64_t(n) * n * 32;
    return true;
}

void ImpostorTextures::bind(const render::ShaderProgram& program, uint32_t baseUnit) const {
    gl::glBindTextureUnit(baseUnit, albedo_);
    gl::glBindTextureUnit(baseUnit + 1, normalDepth_);
    gl::glBindTextureUnit(baseUnit + 2, tableViews_);
    gl::glBindTextureUnit(baseUnit + 3, tableWeights_);
    program.set("impostorAlbedo", int(baseUnit));
    program.set("impostorNormalDepth", int(baseUnit + 1));
    program.set("impostorTableViews", int(baseUnit + 2));
    program.set("impostorTableWeights", int(baseUnit + 3));
    const uint32_t sphere = layout_.sphere == ViewSphere::Hemisphere ? 0u : 1u;
    program.set("impostorLayout", glm::uvec4(layout_.grid, layout_.viewResolution, layout_.padding, sphere));
}

} // namespace hexlod::impostor
