#include "gltf_binary_stream.h"

#include "gltf_layout.h"

#include <array>
#include <cstdio>
#include <filesystem>
#include <vector>

namespace hexlod::apps {
GltfBinaryStream::GltfBinaryStream(std::string output, uint64_t limit)
    : output_(std::move(output)), binTemp_(output_ + ".bin.partial"), outTemp_(output_ + ".partial"),
      limit_(limit) {
    bin_.open(binTemp_, std::ios::binary | std::ios::trunc);
    if (!bin_) refuse("cannot write " + binTemp_);
}

GltfBinaryStream::~GltfBinaryStream() {
    if (!finished_) removeTemporaries();
}

void GltfBinaryStream::removeTemporaries() {
    if (bin_.is_open()) bin_.close();
    std::error_code ec;
    std::filesystem::remove(binTemp_, ec);
    std::filesystem::remove(outTemp_, ec);
}

bool GltfBinaryStream::refuse(const std::string& message) {
    if (error_.empty()) error_ = message;
    return false;
}

bool GltfBinaryStream::reserve(uint64_t bytes) {
    if (!ok()) return false;
    if (gltfPadded(size_) + bytes > limit_) {
        return refuse("the export would pass its limit of " + std::to_string(limit_) + " bytes (" +
                      std::to_string(size_) +
                      " written so far; a .glb holds at most 4 GiB): export fewer "
                      "cells with --cells, drop --flatten, or write .gltf");
    }
    return true;
}

uint64_t GltfBinaryStream::append(const void* data, uint64_t bytes) {
    if (!reserve(bytes)) return size_;
    static const char zeros[4] = {};
    bin_.write(zeros, std::streamsize(gltfPadded(size_) - size_));
    size_ = gltfPadded(size_);
    const uint64_t at = size_;
    bin_.write(static_cast<const char*>(data), std::streamsize(bytes));
    size_ += bytes;
    if (!bin_) refuse("cannot write " + binTemp_ + " (disk full?)");
    return at;
}

bool GltfBinaryStream::finishGlb(const std::string& json) {
    if (!ok()) return false;
    const uint64_t binBytes = gltfPadded(size_);
    const uint64_t total = 12 + 8 + gltfPadded(json.size()) + (size_ ? 8 + binBytes : 0);
    if (total > kGlbMaxBytes)
        return refuse("the .glb would be " + std::to_string(total) + " bytes, past its 4 GiB limit");
    static const char zeros[4] = {};
    bin_.write(zeros, std::streamsize(binBytes - size_));
    bin_.close();
    if (!bin_) return refuse("cannot write " + binTemp_);
    {
        std::ofstream out(outTemp_, std::ios::binary | std::ios::trunc);
        writeGlbPrologue(out, json, size_);
        if (size_) {
            std::ifstream in(binTemp_, std::ios::binary);
            std::vector<char> block(size_t(1) << 20);
            while (in.read(block.data(), std::streamsize(block.size())) || in.gcount() > 0)
                out.write(block.data(), in.gcount());
        }
        out.close();
        if (!out) return refuse("cannot write " + outTemp_ + " (disk full?)");
    }
    std::error_code ec;
    std::filesystem::rename(outTemp_, output_, ec);
    if (ec) return refuse("cannot move the export to " + output_ + ": " + ec.message());
    std::filesystem::remove(binTemp_, ec);
    finished_ = true;
    return true;
}

bool GltfBinaryStream::finishGltf(const std::string& json, const std::string& binPath) {
    if (!ok()) return false;
    bin_.close();
    if (!bin_) return refuse("cannot write " + binTemp_);
    {
        std::ofstream out(outTemp_, std::ios::binary | std::ios::trunc);
        out << json;
        out.close();
        if (!out) return refuse("cannot write " + outTemp_);
    }
    std::error_code ec;
    std::filesystem::rename(binTemp_, binPath, ec);
    if (!ec) std::filesystem::rename(outTemp_, output_, ec);
    if (ec) return refuse("cannot move the export to " + output_ + ": " + ec.message());
    finished_ = true;
    return true;
}

} // namespace hexlod::apps
