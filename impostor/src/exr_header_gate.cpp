#include "exr_header_gate.h"

#include <OpenEXR/openexr.h>

namespace hexlod::impostor {
namespace {

// OpenEXRCore reports its detailed reasons through a callback; keep the first, since later
// ones only follow from it.
void keepFirstError(exr_const_context_t context, exr_result_t code, const char* message) {
    void* user = nullptr;
    if (exr_get_user_data(context, &user) != EXR_ERR_SUCCESS || user == nullptr) return;
    auto& error = *static_cast<std::string*>(user);
    if (error.empty()) error = message ? message : exr_get_default_error_message(code);
}

} // namespace

bool exrHeaderIsSound(const std::string& path, int maxSide, std::string& error) {
    std::string reason;
    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    init.error_handler_fn = keepFirstError;
    init.user_data = &reason;
    init.max_image_width = maxSide;
    init.max_image_height = maxSide;
    init.max_tile_width = maxSide;
    init.max_tile_height = maxSide;
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
    return sound;
}

} // namespace hexlod::impostor
