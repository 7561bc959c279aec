// PNG through png_encoder.h, EXR through OpenEXR's scanline API.
#include "hexlod/render/image_io.h"
#include "hexlod/render/png_encoder.h"

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfOutputFile.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <vector>

namespace hexlod::render {

float linearToSrgb(float linear) {
    float x = std::clamp(linear, 0.0f, 1.0f);
    return x <= 0.0031308f ? 12.92f * x : 1.055f * std::pow(x, 1.0f / 2.4f) - 0.055f;
}

namespace {

// The 8-bit samples of a PNG; false when the image cannot be one.
bool pngSamples(const Image& image, PngTransfer transfer, std::vector<unsigned char>& bytes) {
    if (image.empty() || (image.channels != 4 && image.channels != 1)) return false;
    bytes.resize(image.pixels.size());
    for (size_t i = 0; i < image.pixels.size(); ++i) {
        const bool colour = transfer == PngTransfer::Srgb && image.channels == 4 && i % 4 != 3;
        const float value = colour ? linearToSrgb(image.pixels[i]) : std::clamp(image.pixels[i], 0.0f, 1.0f);
        bytes[i] = static_cast<unsigned char>(std::lround(value * 255.0f));
    }
    return true;
}

const char* kPngShapes = "only non-empty RGBA or single-channel images can be written as PNG";

} // namespace

bool encodePng(const Image& image, PngTransfer transfer, std::vector<uint8_t>& out, std::string& error) {
    std::vector<unsigned char> bytes;
    if (!pngSamples(image, transfer, bytes)) {
        error = kPngShapes;
        return false;
    }
    out = encodePngSamples(bytes, image.width, image.height, image.channels);
    if (out.empty()) {
        error = "cannot encode the PNG";
        return false;
    }
    return true;
}

bool writePng(const std::string& path, const Image& image, std::string& error, PngTransfer transfer) {
    std::vector<uint8_t> png;
    if (!encodePng(image, transfer, png, error)) {
        error = path + ": " + error;
        return false;
    }
    std::ofstream file(path, std::ios::binary);
    file.write(reinterpret_cast<const char*>(png.data()), std::streamsize(png.size()));
    file.close();
    if (!file) {
        error = path + ": cannot write the PNG file";
        return false;
    }
    return true;
}

bool writeExr(const std::string& path, const Image& image, std::string& error) {
    if (image.empty() || (image.channels != 4 && image.channels != 1)) {
        error = path + ": only non-empty RGBA or single-channel images can be written as EXR";
        return false;
    }
    try {
        Imf::Header header(int(image.width), int(image.height));
        header.compression() = Imf::ZIP_COMPRESSION;
        const char* names[4] = {"R", "G", "B", "A"};
        if (image.channels == 1) names[0] = "Z";
        std::vector<half> planes(image.pixels.size());
        size_t planeSize = size_t(image.width) * image.height;
        Imf::FrameBuffer frame;
        for (uint32_t c = 0; c < image.channels; ++c) {
            header.channels().insert(names[c], Imf::Channel(Imf::HALF));
            for (size_t i = 0; i < planeSize; ++i)
                planes[c * planeSize + i] = half(image.pixels[i * image.channels + c]);
            frame.insert(names[c],
                         Imf::Slice(Imf::HALF, reinterpret_cast<char*>(planes.data() + c * planeSize),
                                    sizeof(half), sizeof(half) * image.width));
        }
        Imf::OutputFile file(path.c_str(), header);
        file.setFrameBuffer(frame);
        file.writePixels(int(image.height));
    } catch (const std::exception& e) {
        error = path + ": " + e.what();
        return false;
    }
    return true;
}

bool readExr(const std::string& path, Image& out, std::string& error) {
    try {
        Imf::InputFile file(path.c_str());
        Imath::Box2i window = file.header().dataWindow();
        int64_t width = int64_t(window.max.x) - window.min.x + 1,
                height = int64_t(window.max.y) - window.min.y + 1;
        if (width <= 0 || height <= 0 || width * height > (int64_t(1) << 28)) {
            error = path + ": unusable data window " + std::to_string(width) + "x" + std::to_string(height);
            return false;
        }
        const Imf::ChannelList& channels = file.header().channels();
        std::vector<const char*> names;
        if (channels.findChannel("R") && channels.findChannel("G") && channels.findChannel("B")) {
            names = {"R", "G", "B", "A"};
        } else if (channels.findChannel("Z")) {
            names = {"Z"};
        } else {
            error = path + ": no R, G, B or Z channels";
            return false;
        }
        out = Image(uint32_t(width), uint32_t(height), uint32_t(names.size()), 1.0f);
        Imf::FrameBuffer frame;
        char* base = reinterpret_cast<char*>(out.pixels.data()) -
                     (size_t(window.min.y) * width + window.min.x) * names.size() * sizeof(float);
        for (size_t c = 0; c < names.size(); ++c) {
            // A missing alpha is filled with 1, the fill value of the slice.
            frame.insert(names[c],
                         Imf::Slice(Imf::FLOAT, base + c * sizeof(float), names.size() * sizeof(float),
                                    names.size() * sizeof(float) * width, 1, 1, 1.0));
        }
        file.setFrameBuffer(frame);
        file.readPixels(window.min.y, window.max.y);
    } catch (const std::exception& e) {
        error = path + ": " + e.what();
        return false;
    }
    return true;
}

} // namespace hexlod::render
