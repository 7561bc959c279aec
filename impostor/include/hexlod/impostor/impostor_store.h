// One OpenEXR file per baked shape (ARCHITECTURE.md §4): a tiled atlas, one EXR tile per view,
// half floats, ZIP-compressed, with channels R G B A (albedo and coverage), N.X N.Y N.Z
// (shape-space normal) and Z (depth). Header attributes record the format version, the shape,
// the layout, the bounds and bounding sphere and the content key, so a file is used only for
// exactly what it was baked from.
//
// The store is content-addressed: a file is named by its shape and its bake key, so a mesh or
// layout change looks for another file and the old one is never misread. A file that cannot be
// read, is truncated, or whose header disagrees with its name is deleted and reported as
// corrupt, for the caller to bake again.
#pragma once

#include "hexlod/impostor/impostor_atlas.h"

#include <cstdint>
#include <string>

namespace hexlod::impostor {

inline constexpr int kImpostorFileVersion = 1;

enum class StoreLookup : uint8_t { Missing, Loaded, Corrupt };

class ImpostorStore {
public:
    // Creates `directory` if needed; throws std::filesystem::filesystem_error if it cannot.
    explicit ImpostorStore(std::string directory);

    const std::string& directory() const { return directory_; }
    std::string pathFor(const std::string& shape, uint64_t contentKey) const;

    // Loads the atlas baked for (shape, contentKey) with `layout`. Corrupt: the file existed but
    // was unusable (`reason` says why) and has been deleted.
    StoreLookup load(const std::string& shape, uint64_t contentKey, const ViewLayout& layout,
                     ImpostorAtlas& out, std::string& reason) const;
    // Writes atomically (a temporary file renamed into place). Returns the bytes written.
    bool save(const ImpostorAtlas& atlas, uint64_t& bytes, std::string& error) const;

private:
    std::string directory_;
};

// The file format on its own, for tools and fuzzers: read any path, check nothing but the
// format itself (version, channels, layout attributes and data window).
bool readImpostorFile(const std::string& path, ImpostorAtlas& out, std::string& error);
bool writeImpostorFile(const std::string& path, const ImpostorAtlas& atlas, std::string& error);

} // namespace hexlod::impostor
