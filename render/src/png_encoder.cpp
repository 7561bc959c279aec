// PNG = signature, IHDR, one IDAT of the filtered rows deflated, IEND; each chunk with its CRC.
#include "hexlod/render/png_encoder.h"

#include <zlib.h>

#include <algorithm>
#include <array>
#include <cstdlib>
#include <limits>

namespace hexlod::render {
namespace {

// A low level: the atlases are mostly empty texels and smooth colour, where deflate's longer
// searches gain a few percent of size for several times the time.
constexpr int kDeflateLevel = 3;

void putBigEndian(std::vector<uint8_t>& out, uint32_t value) {
    for (int shift = 24; shift >= 0; shift -= 8) out.push_back(uint8_t(value >> shift));
}

void putChunk(std::vector<uint8_t>& out, const char (&type)[5], std::span<const uint8_t> data) {
    putBigEndian(out, uint32_t(data.size()));
    const size_t typeAt = out.size();
    out.insert(out.end(), type, type + 4);
    out.insert(out.end(), data.begin(), data.end());
    const uLong crc = crc32(0L, out.data() + typeAt, uInt(out.size() - typeAt));
    putBigEndian(out, uint32_t(crc));
}

uint8_t paeth(int a, int b, int c) {
    const int p = a + b - c, pa = std::abs(p - a), pb = std::abs(p - b), pc = std::abs(p - c);
    return uint8_t(pa <= pb && pa <= pc ? a : (pb <= pc ? b : c));
}

// `row` through filter `type` into `out`; returns the sum of the output bytes taken as signed
// values. `above` is the row before (zeros for the first). One loop per type, so that the
// compiler keeps the choice out of the byte loop.
uint64_t filterRow(size_t type, std::span<const uint8_t> row, std::span<const uint8_t> above, size_t bpp,
                   uint8_t* out) {
    const size_t n = row.size();
    const uint8_t* r = row.data();
    const uint8_t* u = above.data();
    switch (type) {
    case 0:
        std::copy(r, r + n, out);
        break;
    case 1:
        for (size_t i = 0; i < n; ++i) out[i] = uint8_t(r[i] - (i >= bpp ? r[i - bpp] : 0));
        break;
    case 2:
        for (size_t i = 0; i < n; ++i) out[i] = uint8_t(r[i] - u[i]);
        break;
    case 3:
        for (size_t i = 0; i < n; ++i) out[i] = uint8_t(r[i] - ((i >= bpp ? r[i - bpp] : 0) + u[i]) / 2);
        break;
    default:
        for (size_t i = 0; i < bpp && i < n; ++i) out[i] = uint8_t(r[i] - u[i]); // Paeth of (0, up, 0)
        for (size_t i = bpp; i < n; ++i) out[i] = uint8_t(r[i] - paeth(r[i - bpp], u[i], u[i - bpp]));
    }
    uint64_t sum = 0;
    for (size_t i = 0; i < n; ++i) sum += uint64_t(std::abs(int(int8_t(out[i]))));
    return sum;
}

// Appends `row` filtered by the filter type that minimises the sum of its bytes taken as
// signed values.
void putFilteredRow(std::vector<uint8_t>& raw, std::span<const uint8_t> row, std::span<const uint8_t> above,
                    uint32_t bpp, std::array<std::vector<uint8_t>, 5>& scratch) {
    uint64_t bestSum = std::numeric_limits<uint64_t>::max();
    size_t best = 0;
    for (size_t type = 0; type < 5; ++type) {
        scratch[type].resize(row.size());
        const uint64_t sum = filterRow(type, row, above, bpp, scratch[type].data());
        if (sum < bestSum) bestSum = sum, best = type;
    }
    raw.push_back(uint8_t(best));
    raw.insert(raw.end(), scratch[best].begin(), scratch[best].end());
}

} // namespace

std::vector<uint8_t> encodePngSamples(std::span<const uint8_t> samples, uint32_t width, uint32_t height,
                                      uint32_t channels) {
    if ((channels != 4 && channels != 1) || width == 0 || height == 0 ||
        uint64_t(width) * height * channels != samples.size() || uint64_t(width) * channels > (1u << 30))
        return {};
    const size_t stride = size_t(width) * channels;
    std::vector<uint8_t> raw;
    raw.reserve((stride + 1) * height);
    const std::vector<uint8_t> zeros(stride, 0);
    std::array<std::vector<uint8_t>, 5> scratch;
    for (uint32_t y = 0; y < height; ++y)
        putFilteredRow(raw, samples.subspan(y * stride, stride),
                       y == 0 ? std::span<const uint8_t>(zeros) : samples.subspan((y - 1) * stride, stride),
                       channels, scratch);

    uLongf deflatedSize = compressBound(uLong(raw.size()));
    std::vector<uint8_t> deflated(deflatedSize);
    if (compress2(deflated.data(), &deflatedSize, raw.data(), uLong(raw.size()), kDeflateLevel) != Z_OK)
        return {};
    deflated.resize(deflatedSize);

    std::vector<uint8_t> png = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    std::vector<uint8_t> header;
    putBigEndian(header, width);
    putBigEndian(header, height);
    // Bit depth 8; colour type 6 (RGBA) or 0 (grey); deflate, adaptive filters, no interlace.
    header.insert(header.end(), {8, uint8_t(channels == 4 ? 6 : 0), 0, 0, 0});
    putChunk(png, "IHDR", header);
    putChunk(png, "IDAT", deflated);
    putChunk(png, "IEND", {});
    return png;
}

} // namespace hexlod::render
