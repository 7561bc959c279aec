// Impostor atlases as tiled OpenEXR files.
#include "hexlod/impostor/impostor_store.h"

#include "exr_header_gate.h"

#include <ImfChannelList.h>
#include <ImfFloatAttribute.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfIntAttribute.h>
#include <ImfStringAttribute.h>
#include <ImfTiledInputFile.h>
#include <ImfTiledOutputFile.h>
#include <ImfVecAttribute.h>

#include <cctype>
#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <unistd.h>

namespace hexlod::impostor {
namespace {

constexpr const char* kChannels[8] = {"R", "G", "B", "A", "N.X", "N.Y", "N.Z", "Z"};

std::string hex(uint64_t value) {
    char text[17];
    std::snprintf(text, sizeof text, "%016" PRIx64, value);
    return text;
}

// Shape names come from grammars and species; keep file names to a safe alphabet.
std::string safeName(const std::string& shape) {
    std::string name;
    for (char c : shape)
        name += (std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_') ? c : '_';
    return name.empty() ? "_" : name;
}

template <typename Attribute> const Attribute* attribute(const Imf::Header& header, const char* name) {
    return header.findTypedAttribute<Attribute>(name);
}

// The two images as eight half planes, interleaved per texel as the frame buffer reads them.
struct HalfPlanes {
    std::vector<half> texels; // 8 per texel
    uint32_t size = 0;
    explicit HalfPlanes(uint32_t atlasSize) : texels(size_t(atlasSize) * atlasSize * 8), size(atlasSize) {}
    Imf::FrameBuffer frame() {
        Imf::FrameBuffer frame;
        for (int c = 0; c < 8; ++c) {
            frame.insert(kChannels[c], Imf::Slice(Imf::HALF, reinterpret_cast<char*>(texels.data() + c),
                                                  8 * sizeof(half), 8 * sizeof(half) * size));
        }
        return frame;
    }
};

} // namespace

bool writeImpostorFile(const std::string& path, const ImpostorAtlas& atlas, std::string& error) {
    const uint32_t size = atlas.layout.atlasSize();
    if (atlas.albedo.width != size || atlas.albedo.height != size || atlas.normalDepth.width != size ||
        atlas.normalDepth.height != size || atlas.albedo.channels != 4 || atlas.normalDepth.channels != 4) {
        error = path + ": the atlas images do not match the layout's " + std::to_string(size) + "^2 texels";
        return false;
    }
    try {
        Imf::Header header{int(size), int(size)};
        header.compression() = Imf::ZIP_COMPRESSION;
        header.setTileDescription(
            Imf::TileDescription(atlas.layout.viewResolution, atlas.layout.viewResolution));
        for (const char* name : kChannels) header.channels().insert(name, Imf::Channel(Imf::HALF));
        header.insert("hexlodFormat", Imf::IntAttribute(kImpostorFileVersion));
        header.insert("hexlodShape", Imf::StringAttribute(atlas.shape));
        header.insert("hexlodSphere",
                      Imf::StringAttribute(atlas.layout.sphere == ViewSphere::Hemisphere ? "hemi-octahedral"
                                                                                         : "octahedral"));
        header.insert("hexlodGrid", Imf::IntAttribute(int(atlas.layout.grid)));
        header.insert("hexlodViewResolution", Imf::IntAttribute(int(atlas.layout.viewResolution)));
        header.insert("hexlodPadding", Imf::IntAttribute(int(atlas.layout.padding)));
        header.insert("hexlodBoundsMin",
                      Imf::V3fAttribute({atlas.boundsMin.x, atlas.boundsMin.y, atlas.boundsMin.z}));
        header.insert("hexlodBoundsMax",
                      Imf::V3fAttribute({atlas.boundsMax.x, atlas.boundsMax.y, atlas.boundsMax.z}));
        header.insert("hexlodCentre", Imf::V3fAttribute({atlas.centre.x, atlas.centre.y, atlas.centre.z}));
        header.insert("hexlodRadius", Imf::FloatAttribute(atlas.radius));
        header.insert("hexlodContentKey", Imf::StringAttribute(hex(atlas.contentKey)));
        HalfPlanes planes(size);
        for (size_t i = 0; i < size_t(size) * size; ++i) {
            for (int c = 0; c < 4; ++c) {
                planes.texels[i * 8 + c] = half(atlas.albedo.pixels[i * 4 + c]);
                planes.texels[i * 8 + 4 + c] = half(atlas.normalDepth.pixels[i * 4 + c]);
            }
        }
        Imf::TiledOutputFile file(path.c_str(), header);
        file.setFrameBuffer(planes.frame());
        file.writeTiles(0, file.numXTiles() - 1, 0, file.numYTiles() - 1);
    } catch (const std::exception& e) {
        error = path + ": " + e.what();
        return false;
    }
    return true;
}

bool readImpostorFile(const std::string& path, ImpostorAtlas& out, std::string& error) {
    if (!exrHeaderIsSound(path, int(kMaxAtlasSize), int(kMaxViewResolution), error)) {
        error = path + ": " + error;
        return false;
    }
    try {
        Imf::TiledInputFile file(path.c_str());
        const Imf::Header& header = file.header();
        auto format = attribute<Imf::IntAttribute>(header, "hexlodFormat");
        if (!format) {
            error = path + ": not a hexlod impostor (no hexlodFormat attribute)";
            return false;
        }
        if (format->value() != kImpostorFileVersion) {
            error = path + ": impostor format version " + std::to_string(format->value()) +
                    ", this build reads " + std::to_string(kImpostorFileVersion);
            return false;
        }
        auto shape = attribute<Imf::StringAttribute>(header, "hexlodShape");
        auto sphere = attribute<Imf::StringAttribute>(header, "hexlodSphere");
        auto grid = attribute<Imf::IntAttribute>(header, "hexlodGrid");
        auto resolution = attribute<Imf::IntAttribute>(header, "hexlodViewResolution");
        auto padding = attribute<Imf::IntAttribute>(header, "hexlodPadding");
        auto boundsMin = attribute<Imf::V3fAttribute>(header, "hexlodBoundsMin");
        auto boundsMax = attribute<Imf::V3fAttribute>(header, "hexlodBoundsMax");
        auto centre = attribute<Imf::V3fAttribute>(header, "hexlodCentre");
        auto radius = attribute<Imf::FloatAttribute>(header, "hexlodRadius");
        auto key = attribute<Imf::StringAttribute>(header, "hexlodContentKey");
        if (!shape || !sphere || !grid || !resolution || !padding || !boundsMin || !boundsMax || !centre ||
            !radius || !key) {
            error = path + ": a hexlod impostor attribute is missing";
            return false;
        }
        ImpostorAtlas atlas;
        atlas.shape = shape->value();
        if (sphere->value() != "hemi-octahedral" && sphere->value() != "octahedral") {
            error = path + ": unknown view sphere '" + sphere->value() + "'";
            return false;
        }
        atlas.layout.sphere =
            sphere->value() == "octahedral" ? ViewSphere::FullSphere : ViewSphere::Hemisphere;
        atlas.layout.grid = uint32_t(std::max(grid->value(), 0));
        atlas.layout.viewResolution = uint32_t(std::max(resolution->value(), 0));
        atlas.layout.padding = uint32_t(std::max(padding->value(), 0));
        std::string layoutError;
        if (!atlas.layout.validate(layoutError)) {
            error = path + ": " + layoutError;
            return false;
        }
        const uint32_t size = atlas.layout.atlasSize();
        Imath::Box2i window = header.dataWindow();
        if (window.min.x != 0 || window.min.y != 0 || window.max.x != int(size) - 1 ||
            window.max.y != int(size) - 1) {
            error = path + ": data window does not match the layout's " + std::to_string(size) + "^2 atlas";
            return false;
        }
        for (const char* name : kChannels) {
            const Imf::Channel* channel = header.channels().findChannel(name);
            if (!channel || channel->type != Imf::HALF) {
                error = path + ": channel " + name + " is missing or not half";
                return false;
            }
        }
        atlas.boundsMin = {boundsMin->value().x, boundsMin->value().y, boundsMin->value().z};
        atlas.boundsMax = {boundsMax->value().x, boundsMax->value().y, boundsMax->value().z};
        atlas.centre = {centre->value().x, centre->value().y, centre->value().z};
        atlas.radius = radius->value();
        // Reconstruction and the cull divide by the radius and place views around the centre.
        if (!(std::isfinite(atlas.radius) && atlas.radius > 0.0f) ||
            !std::isfinite(atlas.centre.x + atlas.centre.y + atlas.centre.z) ||
            !std::isfinite(atlas.boundsMin.x + atlas.boundsMin.y + atlas.boundsMin.z) ||
            !std::isfinite(atlas.boundsMax.x + atlas.boundsMax.y + atlas.boundsMax.z)) {
            error = path + ": the bounding sphere needs a positive radius, and it and the bounds finite "
                           "values";
            return false;
        }
        atlas.contentKey = std::strtoull(key->value().c_str(), nullptr, 16);
        HalfPlanes planes(size);
        file.setFrameBuffer(planes.frame());
        file.readTiles(0, file.numXTiles() - 1, 0, file.numYTiles() - 1);
        atlas.albedo = render::Image(size, size, 4);
        atlas.normalDepth = render::Image(size, size, 4);
        for (size_t i = 0; i < size_t(size) * size; ++i) {
            for (int c = 0; c < 4; ++c) {
                atlas.albedo.pixels[i * 4 + c] = float(planes.texels[i * 8 + c]);
                atlas.normalDepth.pixels[i * 4 + c] = float(planes.texels[i * 8 + 4 + c]);
            }
        }
        out = std::move(atlas);
    } catch (const std::exception& e) {
        error = path + ": " + e.what();
        return false;
    }
    return true;
}

ImpostorStore::ImpostorStore(std::string directory) : directory_(std::move(directory)) {
    std::filesystem::create_directories(directory_);
}

std::string ImpostorStore::pathFor(const std::string& shape, uint64_t contentKey) const {
    return (std::filesystem::path(directory_) / (safeName(shape) + "-" + hex(contentKey) + ".exr")).string();
}

StoreLookup ImpostorStore::load(const std::string& shape, uint64_t contentKey, const ViewLayout& layout,
                                ImpostorAtlas& out, std::string& reason) const {
    const std::string path = pathFor(shape, contentKey);
    std::error_code ec;
    if (!std::filesystem::exists(path, ec)) return StoreLookup::Missing;
    ImpostorAtlas atlas;
    bool usable = readImpostorFile(path, atlas, reason);
    if (usable &&
        (atlas.shape != shape || atlas.contentKey != contentKey || atlas.layout.sphere != layout.sphere ||
         atlas.layout.grid != layout.grid || atlas.layout.viewResolution != layout.viewResolution ||
         atlas.layout.padding != layout.padding)) {
        reason = path + ": its header does not match the shape, key or layout it is filed under";
        usable = false;
    }
    if (!usable) {
        std::filesystem::remove(path, ec);
        return StoreLookup::Corrupt;
    }
    out = std::move(atlas);
    return StoreLookup::Loaded;
}

bool ImpostorStore::save(const ImpostorAtlas& atlas, uint64_t& bytes, std::string& error) const {
    const std::string path = pathFor(atlas.shape, atlas.contentKey);
    const std::string temporary = path + ".tmp" + std::to_string(::getpid());
    if (!writeImpostorFile(temporary, atlas, error)) {
        std::error_code ec;
        std::filesystem::remove(temporary, ec);
        return false;
    }
    std::error_code ec;
    bytes = std::filesystem::file_size(temporary, ec);
    std::filesystem::rename(temporary, path, ec);
    if (ec) {
        error = path + ": " + ec.message();
        std::filesystem::remove(temporary, ec);
        return false;
    }
    return true;
}

} // namespace hexlod::impostor
