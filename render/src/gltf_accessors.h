// Bounds-checked reads of glTF accessors and base-colour textures from a tinygltf model, for
// gltf_mesh_loader.cpp. Every read checks indices, strides and byte ranges against the buffers,
// so a malformed file is an error message and never an out-of-bounds read.
#pragma once

#include <tiny_gltf.h>

#include <glm/glm.hpp>

#include <string>
#include <vector>

namespace hexlod::render {

// Reads accessor `index` as `components` floats per element (normalised integers scaled to
// [0, 1] or [-1, 1], plain integers converted). The accessor's own component count must be
// `components` or, with `allowFewer`, at least 3 (vec3 colours read as vec4 get alpha 1).
bool readFloatAccessor(const tinygltf::Model& model, int index, int components, std::vector<float>& out,
                       std::string& error);
// Reads an index accessor (unsigned byte, short or int scalars).
bool readIndexAccessor(const tinygltf::Model& model, int index, std::vector<uint32_t>& out,
                       std::string& error);

// Linear RGBA of a decoded texture image at `uv` (nearest texel, repeat wrap, sRGB decoded),
// after the textureInfo's KHR_texture_transform; invalid when the image holds no decoded
// 8-bit pixels.
struct TextureSampler {
    const tinygltf::Image* image = nullptr;
    glm::vec2 offset{0.0f}, scale{1.0f};
    float rotation = 0.0f; // radians
    bool valid() const;
    glm::vec4 sample(glm::vec2 uv) const;
    glm::vec4 mean() const;
};
// The sampler of a material's baseColorTexture, invalid when it has none or it was not decoded.
TextureSampler baseColorTexture(const tinygltf::Model& model, int material);

} // namespace hexlod::render
