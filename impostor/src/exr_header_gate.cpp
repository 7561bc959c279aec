#include "exr_header_gate.h"

#include <OpenEXR/openexr.h>

#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>
#include <string_view>
#include <vector>

namespace hexlod::impostor {
namespace {

// The attribute types an impostor file holds, with their sizes (0: a string, any size the file
// holds; -1: a channel list). OpenEXR's C++ reader reads a known type by its own length, not
// the size the header states, so a size that disagrees would put it out of step with
// OpenEXRCore's reading; and it allocates an unknown type's stated size up front. Any other
// type, or a size that disagrees, is refused before either reader sees the file.
struct AttributeType {
    std::string_view name;
    int size;
};
constexpr AttributeType kAttributeTypes[] = {
    {"box2i", 16},    {"chlist", -1}, {"compression", 1}, {"float", 4}, {"int", 4},
    {"lineOrder", 1}, {"string", 0},  {"tiledesc", 9},    {"v2f", 8},   {"v3f", 12},
};
constexpr size_t kMaxHeaderBytes = 1 << 16;

// A channel list as OpenEXR's C++ reader reads it: entries of a name, 16 bytes of type,
// linearity and sampling, up to an empty name, which must be the list's last stated byte.
bool channelListEndsWhereStated(std::string_view value) {
    size_t at = 0;
    while (at < value.size() && value[at] != '\0') {
        const size_t end = value.find('\0', at);
        if (end == std::string_view::npos) return false;
        at = end + 1 + 16;
    }
    return at + 1 == value.size();
}

bool attributesAreKnownAndSized(const std::string& path, std::string& error) {
    std::ifstream file(path, std::ios::binary);
    std::vector<char> bytes(kMaxHeaderBytes);
    file.read(bytes.data(), std::streamsize(bytes.size()));
    bytes.resize(size_t(file.gcount()));
    const std::string_view header(bytes.data(), bytes.size());
    size_t at = 8; // magic number and version
    while (at < header.size() && header[at] != '\0') {
        const size_t nameEnd = header.find('\0', at);
        const size_t typeEnd = nameEnd == std::string_view::npos ? nameEnd : header.find('\0', nameEnd + 1);
        if (typeEnd == std::string_view::npos || typeEnd + 5 > header.size()) break;
        const std::string_view name = header.substr(at, nameEnd - at);
        const std::string_view type = header.substr(nameEnd + 1, typeEnd - nameEnd - 1);
        int32_t size = 0;
        std::memcpy(&size, header.data() + typeEnd + 1, 4);
        at = typeEnd + 5;
        const AttributeType* known = nullptr;
        for (const AttributeType& t : kAttributeTypes)
            if (t.name == type) known = &t;
        if (!known) {
            error = "attribute '" + std::string(name) + "' has a type an impostor does not use ('" +
                    std::string(type) + "')";
            return false;
        }
        if (size < 0 || size_t(size) > header.size() - at || (known->size > 0 && size != known->size) ||
            (known->size < 0 && !channelListEndsWhereStated(header.substr(at, size_t(size))))) {
            error = "attribute '" + std::string(name) + "' states a size of " + std::to_string(size) +
                    " bytes its type or the file does not hold";
            return false;
        }
        at += size_t(size);
    }
    if (at >= header.size()) {
        error = "the header does not end within the first " + std::to_string(kMaxHeaderBytes) + " bytes";
        return false;
    }
    return true;
}

// OpenEXRCore reports its detailed reasons through a callback; keep the first, since later
// ones only follow from it.
void keepFirstError(exr_const_context_t context, exr_result_t code, const char* message) {
    void* user = nullptr;
    if (exr_get_user_data(context, &user) != EXR_ERR_SUCCESS || user == nullptr) return;
    auto& error = *static_cast<std::string*>(user);
    if (error.empty()) error = message ? message : exr_get_default_error_message(code);
}

} // namespace

bool exrHeaderIsSound(const std::string& path, int maxImageSide, int maxTileSide, std::string& error) {
    std::string reason;
    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    init.error_handler_fn = keepFirstError;
    init.user_data = &reason;
    init.max_image_width = maxImageSide;
    init.max_image_height = maxImageSide;
    init.max_tile_width = maxTileSide;
    init.max_tile_height = maxTileSide;
    exr_context_t context = nullptr;
    const exr_result_t opened = exr_start_read(&context, path.c_str(), &init);
    if (opened != EXR_ERR_SUCCESS) {
        error = reason.empty() ? exr_get_default_error_message(opened) : reason;
        exr_finish(&context);
        return false;
    }
    int parts = 0;
    exr_storage_t storage = EXR_STORAGE_LAST_TYPE;
    bool sound = exr_get_count(context, &parts) == EXR_ERR_SUCCESS && parts == 1 &&
                 exr_get_storage(context, 0, &storage) == EXR_ERR_SUCCESS && storage == EXR_STORAGE_TILED;
    if (!sound) error = "not a single-part tiled EXR file";
    exr_finish(&context);
    return sound && attributesAreKnownAndSized(path, error);
}

} // namespace hexlod::impostor
