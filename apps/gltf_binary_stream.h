// The binary side of a glTF export: appends bytes to a temporary file as they are produced, so
// a large export never holds its buffer in memory, then assembles the final .glb (header, JSON
// chunk, BIN chunk; glTF 2.0 specification §4.4) or writes the .gltf JSON beside a .bin file.
// Output files appear only when complete (written under a temporary name, then renamed); on
// failure or destruction before finishing, every temporary file is removed.
#pragma once

#include <cstdint>
#include <fstream>
#include <string>

namespace hexlod::apps {

// The glb container counts its length in 32 bits.
inline constexpr uint64_t kGlbMaxBytes = 0xffffffffull;

class GltfBinaryStream {
public:
    // `output` is the final path; `limit` the most bytes the buffer may reach.
    GltfBinaryStream(std::string output, uint64_t limit);
    ~GltfBinaryStream();
    GltfBinaryStream(const GltfBinaryStream&) = delete;
    GltfBinaryStream& operator=(const GltfBinaryStream&) = delete;

    bool ok() const { return error_.empty(); }
    const std::string& error() const { return error_; }
    uint64_t size() const { return size_; }

    // Whether `bytes` more (after padding to 4) still fit under the limit; sets the error if not.
    bool reserve(uint64_t bytes);
    // Appends at the next 4-byte boundary and returns the offset written at. Check ok() after.
    uint64_t append(const void* data, uint64_t bytes);

    // Stops the export with `message` (kept if an error is already set); returns false.
    bool refuse(const std::string& message);

    // Writes `json` and the buffer as one .glb at the output path.
    bool finishGlb(const std::string& json);
    // Writes `json` at the output path and the buffer at `binPath` (the JSON's buffer uri).
    bool finishGltf(const std::string& json, const std::string& binPath);

private:
    void removeTemporaries();

    std::string output_, binTemp_, outTemp_;
    std::ofstream bin_;
    uint64_t size_ = 0, limit_ = 0;
    std::string error_;
    bool finished_ = false;
};

} // namespace hexlod::apps
