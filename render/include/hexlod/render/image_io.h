// Images to and from files: PNG for people (8-bit sRGB through stb_image_write) and OpenEXR
// for data (half floats, linear, lossless ZIP compression).
#pragma once

#include "hexlod/render/image.h"

#include <string>

namespace hexlod::render {

// Writes an RGBA or single-channel image as 8-bit PNG. Colour is taken as linear and encoded
// to sRGB; alpha and single-channel images are written as they are, clamped to [0, 1].
bool writePng(const std::string& path, const Image& image, std::string& error);

// Writes RGBA (channels R, G, B, A) or single-channel (channel Z) half-float EXR.
bool writeExr(const std::string& path, const Image& image, std::string& error);
// Reads an EXR written by writeExr, or any EXR with R, G, B[, A] or Z channels.
bool readExr(const std::string& path, Image& out, std::string& error);

// Linear to sRGB transfer, for one channel in [0, 1].
float linearToSrgb(float linear);

} // namespace hexlod::render
