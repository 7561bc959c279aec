#include "zstd_frame.h"

#include <zstd.h>

#include <algorithm>
#include <cstdlib>
#include <memory>
#include <new>

namespace hexlod::grammar::detail {
namespace {

struct ZstdContexts {
    std::unique_ptr<ZSTD_CCtx, size_t (*)(ZSTD_CCtx*)> compress{ZSTD_createCCtx(), ZSTD_freeCCtx};
    std::unique_ptr<ZSTD_DCtx, size_t (*)(ZSTD_DCtx*)> decompress{ZSTD_createDCtx(), ZSTD_freeDCtx};
};
// One pair per thread: creating a level-3 context costs more than encoding a small batch.
ZstdContexts& contexts() {
    thread_local ZstdContexts c;
    return c;
}

// Grown with realloc, which leaves the new bytes uninitialised (zstd writes them) and moves
// large blocks by remapping their pages instead of copying them.
class Scratch {
public:
    Scratch() = default;
    Scratch(const Scratch&) = delete;
    Scratch& operator=(const Scratch&) = delete;
    ~Scratch() { std::free(data_); }
    uint8_t* data() const { return data_; }
    size_t capacity() const { return capacity_; }
    void reserve(size_t bytes) {
        if (bytes <= capacity_) return;
        void* grown = std::realloc(data_, bytes);
        if (!grown) throw std::bad_alloc();
        data_ = static_cast<uint8_t*>(grown);
        capacity_ = bytes;
    }
    void release() {
        std::free(data_);
        data_ = nullptr;
        capacity_ = 0;
    }

private:
    uint8_t* data_ = nullptr;
    size_t capacity_ = 0;
};
// Three per thread: what a decoder decompresses into, what an encoder lays its body out in,
// and the frame it compresses that into (a payload's own bytes are then copied at their size).
Scratch& decodeScratch() {
    thread_local Scratch s;
    return s;
}
Scratch& bodyScratch() {
    thread_local Scratch s;
    return s;
}
Scratch& frameScratch() {
    thread_local Scratch s;
    return s;
}

void releaseIfLarge(Scratch& s) {
    if (s.capacity() > kKeptScratchBytes) s.release();
}

} // namespace

size_t compressFrame(std::span<const uint8_t> body, int level, std::vector<uint8_t>& out, size_t offset) {
    Scratch& frame = frameScratch();
    frame.reserve(ZSTD_compressBound(body.size()));
    ZSTD_CCtx* cctx = contexts().compress.get();
    ZSTD_CCtx_reset(cctx, ZSTD_reset_session_and_parameters);
    ZSTD_CCtx_setParameter(cctx, ZSTD_c_compressionLevel, level);
    const size_t bytes = ZSTD_compress2(cctx, frame.data(), frame.capacity(), body.data(), body.size());
    // The bound makes the only failure a bad level, which zstd clamps instead of failing.
    const size_t frameBytes = ZSTD_isError(bytes) ? 0 : bytes;
    // Sized once, to what a payload kept in a cache needs: neither the bound nor zeros.
    out.reserve(offset + frameBytes);
    out.resize(offset);
    out.insert(out.end(), frame.data(), frame.data() + frameBytes);
    releaseIfLarge(frame);
    return frameBytes;
}

uint8_t* encoderBody(size_t bytes) {
    bodyScratch().reserve(bytes);
    return bodyScratch().data();
}

// One byte of room beyond the expected size tells "the frame holds more" apart from "the
// frame ends here".
bool decompressFrame(std::span<const uint8_t> frame, uint64_t expected, std::span<const uint8_t>& result,
                     std::string& error) {
    const unsigned long long declared = ZSTD_getFrameContentSize(frame.data(), frame.size());
    if (declared == ZSTD_CONTENTSIZE_ERROR) return error = "body is not a zstd frame", false;
    if (declared != ZSTD_CONTENTSIZE_UNKNOWN && declared != expected)
        return error = "body declares " + std::to_string(declared) + " bytes, the header needs " +
                       std::to_string(expected),
               false;
    ZSTD_DCtx* dctx = contexts().decompress.get();
    ZSTD_DCtx_reset(dctx, ZSTD_reset_session_only);
    const uint64_t limit = expected + 1;
    Scratch& body = decodeScratch();
    // Room the scratch already has is used at once; beyond it the body grows only with what
    // the frame delivers.
    size_t room = static_cast<size_t>(std::min<uint64_t>(
        limit, std::max<uint64_t>({frame.size() * 8, uint64_t(1) << 16, uint64_t(body.capacity())})));
    body.reserve(room);
    ZSTD_inBuffer in{frame.data(), frame.size(), 0};
    size_t produced = 0;
    size_t remaining = 1; // zstd's hint; 0 once the frame is complete
    while (true) {
        if (produced == room) {
            if (room == limit) break;
            room = static_cast<size_t>(std::min<uint64_t>(limit, uint64_t(room) * 2));
            body.reserve(room);
        }
        ZSTD_outBuffer out{body.data(), room, produced};
        const size_t consumed = in.pos;
        remaining = ZSTD_decompressStream(dctx, &out, &in);
        if (ZSTD_isError(remaining))
            return error = std::string("corrupt body: ") + ZSTD_getErrorName(remaining), false;
        const bool stalled = out.pos == produced && in.pos == consumed;
        produced = out.pos;
        if (remaining == 0) break;
        if (stalled) return error = "truncated body", false; // it had room to write, so it lacks input
    }
    if (remaining != 0 || produced > expected)
        return error = "body decodes to more than the header says", false;
    if (in.pos != in.size) return error = "trailing bytes after the body", false;
    if (produced != expected)
        return error = "body decodes to " + std::to_string(produced) + " bytes, the header needs " +
                       std::to_string(expected),
               false;
    result = std::span<const uint8_t>(body.data(), produced);
    return true;
}

ScratchRelease::~ScratchRelease() {
    releaseIfLarge(decodeScratch());
    releaseIfLarge(bodyScratch());
}

ThreadScratch threadScratch() {
    return {decodeScratch().capacity(), bodyScratch().capacity(), frameScratch().capacity()};
}

} // namespace hexlod::grammar::detail
