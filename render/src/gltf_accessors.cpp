// Bounds-checked glTF accessor and texture reads (gltf_accessors.h), after the glTF 2.0
// specification §3.6 (accessors: strides, normalised integers, alignment).
#include "gltf_accessors.h"

#include <cmath>
#include <cstring>

namespace hexlod::render {
namespace {

int componentBytes(int type) {
    switch (type) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
        return 1;
    case TINYGLTF_COMPONENT_TYPE_SHORT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
        return 2;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
    case TINYGLTF_COMPONENT_TYPE_FLOAT:
        return 4;
    default:
        return 0;
    }
}

int typeComponents(int type) {
    switch (type) {
    case TINYGLTF_TYPE_SCALAR:
        return 1;
    case TINYGLTF_TYPE_VEC2:
        return 2;
    case TINYGLTF_TYPE_VEC3:
        return 3;
    case TINYGLTF_TYPE_VEC4:
        return 4;
    default:
        return 0;
    }
}

double component(const unsigned char* p, int type, bool normalized) {
    switch (type) {
    case TINYGLTF_COMPONENT_TYPE_BYTE: {
        const double v = double(int8_t(*p));
        return normalized ? std::max(v / 127.0, -1.0) : v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
        return normalized ? double(*p) / 255.0 : double(*p);
    case TINYGLTF_COMPONENT_TYPE_SHORT: {
        int16_t v;
        std::memcpy(&v, p, 2);
        return normalized ? std::max(double(v) / 32767.0, -1.0) : double(v);
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
        uint16_t v;
        std::memcpy(&v, p, 2);
        return normalized ? double(v) / 65535.0 : double(v);
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: {
        uint32_t v;
        std::memcpy(&v, p, 4);
        return double(v);
    }
    default: {
        float v;
        std::memcpy(&v, p, 4);
        return double(v);
    }
    }
}

// The element bytes of an accessor after every range check, or null with `error`.
struct AccessorView {
    const unsigned char* data = nullptr;
    size_t stride = 0, count = 0;
    int components = 0, componentType = 0;
    bool normalized = false;
};

bool viewOf(const tinygltf::Model& model, int index, AccessorView& view, std::string& error) {
    if (index < 0 || size_t(index) >= model.accessors.size()) {
        error = "accessor " + std::to_string(index) + " does not exist";
        return false;
    }
    const tinygltf::Accessor& a = model.accessors[size_t(index)];
    const std::string name = "accessor " + std::to_string(index);
    if (a.sparse.isSparse) {
        error = name + " is sparse, which is not supported";
        return false;
    }
    const int size = componentBytes(a.componentType), components = typeComponents(a.type);
    if (size == 0 || components == 0) {
        error = name + " has an unsupported component type or element type";
        return false;
    }
    if (a.bufferView < 0 || size_t(a.bufferView) >= model.bufferViews.size()) {
        error = name + " has no buffer view";
        return false;
    }
    const tinygltf::BufferView& bv = model.bufferViews[size_t(a.bufferView)];
    if (bv.buffer < 0 || size_t(bv.buffer) >= model.buffers.size()) {
        error = name + ": buffer view " + std::to_string(a.bufferView) + " names no buffer";
        return false;
    }
    const std::vector<unsigned char>& buffer = model.buffers[size_t(bv.buffer)].data;
    const size_t element = size_t(size) * size_t(components);
    const size_t stride = bv.byteStride ? bv.byteStride : element;
    if (stride < element || a.count == 0 || a.count > (size_t(1) << 28)) {
        error = name + " has a bad stride or count";
        return false;
    }
    const size_t span = stride * (a.count - 1) + element;
    if (bv.byteOffset > buffer.size() || bv.byteLength > buffer.size() - bv.byteOffset ||
        a.byteOffset > bv.byteLength || span > bv.byteLength - a.byteOffset) {
        error = name + " reaches past the end of its buffer";
        return false;
    }
    view = {buffer.data() + bv.byteOffset + a.byteOffset,
            stride,
            a.count,
            components,
            a.componentType,
            a.normalized};
    return true;
}

float srgbToLinear(float c) {
    return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
}

} // namespace

bool readFloatAccessor(const tinygltf::Model& model, int index, int components, std::vector<float>& out,
                       std::string& error) {
    AccessorView view;
    if (!viewOf(model, index, view, error)) return false;
    const bool colourPadding = components == 4 && view.components == 3;
    if (view.components != components && !colourPadding) {
        error = "accessor " + std::to_string(index) + " has " + std::to_string(view.components) +
                " components, expected " + std::to_string(components);
        return false;
    }
    const size_t size = size_t(componentBytes(view.componentType));
    out.resize(view.count * size_t(components));
    for (size_t i = 0; i < view.count; ++i) {
        const unsigned char* element = view.data + i * view.stride;
        for (int c = 0; c < components; ++c) {
            const double v = c < view.components
                                 ? component(element + size * size_t(c), view.componentType, view.normalized)
                                 : 1.0;
            out[i * size_t(components) + size_t(c)] = static_cast<float>(v);
        }
    }
    return true;
}

bool readIndexAccessor(const tinygltf::Model& model, int index, std::vector<uint32_t>& out,
                       std::string& error) {
    AccessorView view;
    if (!viewOf(model, index, view, error)) return false;
    if (view.components != 1 || view.componentType == TINYGLTF_COMPONENT_TYPE_FLOAT ||
        view.componentType == TINYGLTF_COMPONENT_TYPE_BYTE ||
        view.componentType == TINYGLTF_COMPONENT_TYPE_SHORT) {
        error = "index accessor " + std::to_string(index) + " is not unsigned integer scalars";
        return false;
    }
    out.resize(view.count);
    for (size_t i = 0; i < view.count; ++i)
        out[i] = static_cast<uint32_t>(component(view.data + i * view.stride, view.componentType, false));
    return true;
}

bool TextureSampler::valid() const {
    return image && image->width > 0 && image->height > 0 && image->bits == 8 && image->component >= 3 &&
           image->image.size() >= size_t(image->width) * size_t(image->height) * size_t(image->component);
}

glm::vec4 TextureSampler::sample(glm::vec2 in) const {
    // KHR_texture_transform: translation * rotation * scale, rotation as the extension's column-major matrix.
    const glm::vec2 scaled = in * scale;
    const float c = std::cos(rotation), s = std::sin(rotation);
    const glm::vec2 uv = offset + glm::vec2(c * scaled.x - s * scaled.y, s * scaled.x + c * scaled.y);
    const auto wrap = [](float f, int n) {
        if (!std::isfinite(f)) return 0;
        const int i = static_cast<int>(std::floor((f - std::floor(f)) * float(n)));
        return std::min(std::max(i, 0), n - 1);
    };
    const size_t x = size_t(wrap(uv.x, image->width)), y = size_t(wrap(uv.y, image->height));
    const unsigned char* p = image->image.data() + (y * size_t(image->width) + x) * size_t(image->component);
    return {srgbToLinear(p[0] / 255.0f), srgbToLinear(p[1] / 255.0f), srgbToLinear(p[2] / 255.0f),
            image->component == 4 ? p[3] / 255.0f : 1.0f};
}

glm::vec4 TextureSampler::mean() const {
    glm::dvec4 sum(0.0);
    const size_t pixels = size_t(image->width) * size_t(image->height);
    for (size_t i = 0; i < pixels; ++i) {
        const unsigned char* p = image->image.data() + i * size_t(image->component);
        sum += glm::dvec4(srgbToLinear(p[0] / 255.0f), srgbToLinear(p[1] / 255.0f),
                          srgbToLinear(p[2] / 255.0f), image->component == 4 ? p[3] / 255.0 : 1.0);
    }
    return glm::vec4(sum / double(pixels));
}

TextureSampler baseColorTexture(const tinygltf::Model& model, int material) {
    if (material < 0 || size_t(material) >= model.materials.size()) return {};
    const tinygltf::TextureInfo& info =
        model.materials[size_t(material)].pbrMetallicRoughness.baseColorTexture;
    const int texture = info.index;
    if (texture < 0 || size_t(texture) >= model.textures.size()) return {};
    const int source = model.textures[size_t(texture)].source;
    if (source < 0 || size_t(source) >= model.images.size()) return {};
    TextureSampler sampler{.image = &model.images[size_t(source)]};
    if (const auto it = info.extensions.find("KHR_texture_transform"); it != info.extensions.end()) {
        const tinygltf::Value& t = it->second;
        const auto number = [](const tinygltf::Value& v, float fallback) {
            return v.IsNumber() ? static_cast<float>(v.GetNumberAsDouble()) : fallback;
        };
        const auto pair = [&](const char* key, glm::vec2 fallback) {
            const tinygltf::Value& v = t.Get(key);
            if (!v.IsArray() || v.ArrayLen() != 2) return fallback;
            return glm::vec2(number(v.Get(0), fallback.x), number(v.Get(1), fallback.y));
        };
        sampler.offset = pair("offset", sampler.offset);
        sampler.scale = pair("scale", sampler.scale);
        sampler.rotation = number(t.Get("rotation"), 0.0f);
    }
    return sampler.valid() ? sampler : TextureSampler{};
}

} // namespace hexlod::render
