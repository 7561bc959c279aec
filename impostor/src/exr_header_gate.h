// A check of an EXR file's header by OpenEXRCore before OpenEXR's C++ reader opens it.
// The C++ reader of OpenEXR 3.1 trusts the sizes a header states: a 562-byte file that
// claims an 800 MB attribute gets 800 MB allocated before anything is read (found by the
// impostor_file fuzzer). OpenEXRCore checks every size against the file and takes limits on
// the image and tile extents, so a file it accepts costs the C++ reader what the file holds.
#pragma once

#include <string>

namespace hexlod::impostor {

// True when `path` holds one tiled part whose header OpenEXRCore reads, with a data window of
// at most `maxImageSide` and tiles of at most `maxTileSide` texels a side, and only the
// attribute types an impostor uses, each of the size its type has; else false with a reason.
bool exrHeaderIsSound(const std::string& path, int maxImageSide, int maxTileSide, std::string& error);

} // namespace hexlod::impostor
