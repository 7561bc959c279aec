// Images to and from files: PNG for people (8-bit sRGB, png_encoder.h) and OpenEXR
// for data (half floats, linear, lossless ZIP compression).
#pragma once

#include "hexlod/render/image.h"

#include <cstdint>
#include <string>
#include <vector>

namespace hexlod::render {

// How a PNG's first three channels are quantised: Srgb takes them as linear colour and encodes
// them to sRGB; Data writes them as they are (normals, depth), clamped to [0, 1]. Alpha and
// single-channel images are always written as they are.
enum class PngTransfer : uint8_t { Srgb, Data };

// Writes an RGBA or single-channel image as 8-bit PNG.
bool writePng(const std::string& path, const Image& image, std::string& error,
              PngTransfer transfer = PngTransfer::Srgb);
// The same PNG file, in memory (for HTTP replies).
bool encodePng(const Image& image, PngTransfer transfer, std::vector<uint8_t>& out, std::string& error);

// Writes RGBA (channels R, G, B, A) or single-channel (channel Z) half-float EXR.
bool writeExr(const std::string& path, const Image& image, std::string& error);
// Reads an EXR written by writeExr, or any EXR with R, G, B[, A] or Z channels.
bool readExr(const std::string& path, Image& out, std::string& error);

// Linear to sRGB transfer, for one channel in [0, 1].
float linearToSrgb(float linear);

} // namespace hexlod::render
