// libFuzzer target for the impostor store's file reader (impostor_store.h): arbitrary bytes as
// an EXR file must be refused with a reason, or give an atlas whose layout validates and whose
// images have exactly the layout's size, whatever the header claims. OpenEXR itself is the
// system library (not instrumented); what is fuzzed is hexlod's checks around it and that no
// input makes the pair crash, hang or allocate without bound.
#include "fuzz_check.h"

#include "hexlod/impostor/impostor_store.h"

using hexlod::fuzz::allFinite;
using hexlod::fuzz::check;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const hexlod::fuzz::InputFile file(data, size, ".exr");
    hexlod::impostor::ImpostorAtlas atlas;
    std::string error;
    if (!hexlod::impostor::readImpostorFile(file.path(), atlas, error)) {
        check(!error.empty());
        return 0;
    }
    std::string layoutError;
    check(atlas.layout.validate(layoutError));
    const uint32_t side = atlas.layout.atlasSize();
    for (const hexlod::render::Image* image : {&atlas.albedo, &atlas.normalDepth}) {
        check(image->width == side && image->height == side && image->channels == 4);
        check(image->pixels.size() == size_t(side) * side * 4);
    }
    check(allFinite(atlas.radius, atlas.centre.x, atlas.centre.y, atlas.centre.z) && atlas.radius > 0.0f);
    return 0;
}
