// Extruded-set codec (docs/protocol.md, "Extruded set, version 1"). The layout follows the
// terminal-set codec: fields become columns of 32-bit words, smooth ones (building ids,
// footprint and element positions) delta-coded and zigzagged, the rest kept as they are so
// zstd matches repeated axes, sizes and parameter values as whole words. Per-building
// offsets are not stored: they are prefix sums of the counts, so a payload cannot point a
// building outside its arrays.
#include "hexlod/grammar/extruded_set_codec.h"

#include "hexlod/grammar/terminal_set_codec.h"

#include "zstd_frame.h"

#include <stdexcept>

namespace hexlod::grammar {
namespace {

using detail::get;
using detail::put;
using detail::unzigzag;
using detail::zigzag;

constexpr char kMagic[4] = {'H', 'X', 'E', '1'};
constexpr size_t kChecksumOffset = 8;
constexpr size_t kCoveredHeaderOffset = 16;
constexpr uint64_t kBuildingColumns = 6; // id, vertex count, element count, base, height, material
constexpr uint64_t kVertexColumns = 2;   // x, y
constexpr uint64_t kElementColumns = 13; // origin xyz, axis x xyz, axis y xyz, size xy, rule, atom

uint64_t bodyWords(uint64_t buildings, uint64_t vertices, uint64_t elements, uint64_t parameters) {
    return buildings * (kBuildingColumns + parameters) + vertices * kVertexColumns +
           elements * kElementColumns;
}

uint32_t bits(float f) {
    uint32_t u;
    std::memcpy(&u, &f, 4);
    return u;
}
float fromBits(uint32_t u) {
    float f;
    std::memcpy(&f, &u, 4);
    return f;
}

// Writes columns one after another into the body; each column is `count` words.
class ColumnWriter {
public:
    explicit ColumnWriter(std::vector<uint8_t>& body) : body_(body) {}
    template <typename F> void column(size_t count, F wordAt) {
        for (size_t i = 0; i < count; ++i) {
            const uint32_t w = wordAt(i);
            std::memcpy(&body_[at_ + 4 * i], &w, 4);
        }
        at_ += 4 * count;
    }
    template <typename F> void deltaColumn(size_t count, F wordAt) {
        uint32_t previous = 0;
        column(count, [&](size_t i) {
            const uint32_t w = wordAt(i);
            const uint32_t d = zigzag(w - previous);
            previous = w;
            return d;
        });
    }

private:
    std::vector<uint8_t>& body_;
    size_t at_ = 0;
};

class ColumnReader {
public:
    explicit ColumnReader(std::span<const uint8_t> body) : body_(body) {}
    template <typename F> void column(size_t count, F take) {
        for (size_t i = 0; i < count; ++i) {
            uint32_t w;
            std::memcpy(&w, &body_[at_ + 4 * i], 4);
            take(i, w);
        }
        at_ += 4 * count;
    }
    template <typename F> void deltaColumn(size_t count, F take) {
        uint32_t previous = 0;
        column(count, [&](size_t i, uint32_t w) { take(i, previous += unzigzag(w)); });
    }

private:
    std::span<const uint8_t> body_;
    size_t at_ = 0;
};

void checkContiguous(const ExtrudedSet& set, uint32_t parameters) {
    uint64_t vertex = 0, element = 0;
    for (size_t i = 0; i < set.buildings.size(); ++i) {
        const ExtrudedBuilding& b = set.buildings[i];
        if (b.firstVertex != vertex || b.firstElement != element || b.firstParameter != i * parameters)
            throw std::invalid_argument("extruded set: building " + std::to_string(i) +
                                        " does not follow the previous one in its arrays");
        vertex += b.vertexCount;
        element += b.elementCount;
    }
    if (vertex != set.footprints.size() || element != set.elements.size() ||
        set.parameters.size() != set.buildings.size() * parameters)
        throw std::invalid_argument("extruded set: array sizes differ from the buildings' counts");
    if (set.buildings.size() > kExtrudedSetMaxBuildings || vertex > kExtrudedSetMaxVertices ||
        element > kExtrudedSetMaxElements || parameters > kExtrudedSetMaxParameters)
        throw std::invalid_argument("extruded set: exceeds the format's limits");
}

} // namespace

std::vector<uint8_t> encodeExtrudedSet(const ExtrudedSetHeader& header, const ExtrudedSet& set,
                                       int zstdLevel) {
    const size_t nb = set.buildings.size(), nv = set.footprints.size(), ne = set.elements.size();
    const uint32_t p = nb == 0 ? 0 : static_cast<uint32_t>(set.parameters.size() / nb);
    checkContiguous(set, p);

    std::vector<uint8_t> body(4 * bodyWords(nb, nv, ne, p));
    ColumnWriter w(body);
    const auto& bs = set.buildings;
    w.deltaColumn(nb, [&](size_t i) { return bs[i].building; });
    w.column(nb, [&](size_t i) { return bs[i].vertexCount; });
    w.column(nb, [&](size_t i) { return bs[i].elementCount; });
    w.column(nb, [&](size_t i) { return bits(bs[i].baseElevation); });
    w.column(nb, [&](size_t i) { return bits(bs[i].height); });
    w.column(nb, [&](size_t i) { return uint32_t(bs[i].wallMaterial); });
    for (int c = 0; c < 2; ++c) w.deltaColumn(nv, [&](size_t i) { return bits(set.footprints[i][c]); });
    const auto& es = set.elements;
    for (int c = 0; c < 3; ++c) w.deltaColumn(ne, [&](size_t i) { return bits(es[i].origin[c]); });
    for (int c = 0; c < 3; ++c) w.column(ne, [&](size_t i) { return bits(es[i].axisX[c]); });
    for (int c = 0; c < 3; ++c) w.column(ne, [&](size_t i) { return bits(es[i].axisY[c]); });
    for (int c = 0; c < 2; ++c) w.column(ne, [&](size_t i) { return bits(es[i].size[c]); });
    w.column(ne, [&](size_t i) { return es[i].rule; });
    w.column(ne, [&](size_t i) { return es[i].atom; });
    for (uint32_t j = 0; j < p; ++j) w.column(nb, [&](size_t i) { return bits(set.parameters[i * p + j]); });

    std::vector<uint8_t> out;
    const size_t frameBytes = detail::compressFrame(body, zstdLevel, out, kExtrudedSetHeaderBytes);
    std::memcpy(out.data(), kMagic, sizeof(kMagic));
    put<uint32_t>(out, 4, kExtrudedSetFormatVersion);
    put<int32_t>(out, 16, header.cell.q);
    put<int32_t>(out, 20, header.cell.r);
    put<uint32_t>(out, 24, header.grammar);
    put<uint32_t>(out, 28, p);
    put<uint64_t>(out, 32, header.grammarHash);
    put<uint64_t>(out, 40, header.key);
    for (int i = 0; i < 3; ++i) put<double>(out, 48 + 8 * i, header.cellOrigin[i]);
    put<uint32_t>(out, 72, static_cast<uint32_t>(nb));
    put<uint32_t>(out, 76, static_cast<uint32_t>(nv));
    put<uint32_t>(out, 80, static_cast<uint32_t>(ne));
    put<uint32_t>(out, 84, 0);
    put<uint64_t>(out, 88, frameBytes);
    const std::span<const uint8_t> covered(out.data() + kCoveredHeaderOffset,
                                           kExtrudedSetHeaderBytes - kCoveredHeaderOffset);
    put<uint64_t>(out, kChecksumOffset, checksum64(body, checksum64(covered)));
    return out;
}

bool peekExtrudedSet(std::span<const uint8_t> payload, ExtrudedSetPayloadInfo& info, std::string& error) {
    if (payload.size() < kExtrudedSetHeaderBytes)
        return error = "truncated header: " + std::to_string(payload.size()) + " of " +
                       std::to_string(kExtrudedSetHeaderBytes) + " bytes",
               false;
    if (std::memcmp(payload.data(), kMagic, sizeof(kMagic)) != 0)
        return error = "not an extruded set (bad magic)", false;
    info.version = get<uint32_t>(payload, 4);
    if (info.version != kExtrudedSetFormatVersion)
        return error = "unsupported extruded-set version " + std::to_string(info.version) +
                       " (this build reads " + std::to_string(kExtrudedSetFormatVersion) + ")",
               false;
    info.checksum = get<uint64_t>(payload, kChecksumOffset);
    ExtrudedSetHeader& h = info.header;
    h.cell.q = get<int32_t>(payload, 16);
    h.cell.r = get<int32_t>(payload, 20);
    h.grammar = get<uint32_t>(payload, 24);
    info.parametersPerBuilding = get<uint32_t>(payload, 28);
    h.grammarHash = get<uint64_t>(payload, 32);
    h.key = get<uint64_t>(payload, 40);
    for (int i = 0; i < 3; ++i) h.cellOrigin[i] = get<double>(payload, 48 + 8 * i);
    info.buildings = get<uint32_t>(payload, 72);
    info.vertices = get<uint32_t>(payload, 76);
    info.elements = get<uint32_t>(payload, 80);
    info.bodyBytes = get<uint64_t>(payload, 88);
    if (get<uint32_t>(payload, 84) != 0) return error = "reserved header word is not zero", false;
    if (info.buildings > kExtrudedSetMaxBuildings || info.vertices > kExtrudedSetMaxVertices ||
        info.elements > kExtrudedSetMaxElements || info.parametersPerBuilding > kExtrudedSetMaxParameters)
        return error = "counts exceed the format's limits", false;
    if (info.buildings == 0 && info.parametersPerBuilding != 0)
        return error = "parameters per building without buildings", false;
    const uint64_t available = payload.size() - kExtrudedSetHeaderBytes;
    if (available < info.bodyBytes)
        return error = "truncated: " + std::to_string(payload.size()) + " bytes, the header needs " +
                       std::to_string(kExtrudedSetHeaderBytes + info.bodyBytes),
               false;
    if (available > info.bodyBytes) return error = "trailing bytes after the body", false;
    return true;
}

bool decodeExtrudedSet(std::span<const uint8_t> payload, ExtrudedSetHeader& header, ExtrudedSet& set,
                       std::string& error) {
    ExtrudedSetPayloadInfo info;
    if (!peekExtrudedSet(payload, info, error)) return false;
    const size_t nb = info.buildings, nv = info.vertices, ne = info.elements, p = info.parametersPerBuilding;
    const detail::ScratchRelease release;
    std::span<const uint8_t> body;
    if (!detail::decompressFrame(payload.subspan(kExtrudedSetHeaderBytes), 4 * bodyWords(nb, nv, ne, p), body,
                                 error))
        return false;
    if (checksum64(body, checksum64(payload.subspan(kCoveredHeaderOffset,
                                                    kExtrudedSetHeaderBytes - kCoveredHeaderOffset))) !=
        info.checksum)
        return error = "checksum mismatch", false;

    // Sizes are now backed by real bytes, so allocating them is safe.
    ExtrudedSet out;
    out.buildings.resize(nb);
    out.footprints.resize(nv);
    out.elements.resize(ne);
    out.parameters.resize(nb * p);
    ColumnReader r(body);
    auto& bs = out.buildings;
    r.deltaColumn(nb, [&](size_t i, uint32_t w) { bs[i].building = w; });
    r.column(nb, [&](size_t i, uint32_t w) { bs[i].vertexCount = w; });
    r.column(nb, [&](size_t i, uint32_t w) { bs[i].elementCount = w; });
    r.column(nb, [&](size_t i, uint32_t w) { bs[i].baseElevation = fromBits(w); });
    r.column(nb, [&](size_t i, uint32_t w) { bs[i].height = fromBits(w); });
    bool materialOk = true;
    r.column(nb, [&](size_t i, uint32_t w) {
        materialOk = materialOk && w <= 0xffffu;
        bs[i].wallMaterial = static_cast<uint16_t>(w);
    });
    if (!materialOk) return error = "wall material outside 16 bits", false;
    uint64_t vertex = 0, element = 0;
    for (size_t i = 0; i < nb; ++i) {
        bs[i].firstVertex = static_cast<uint32_t>(vertex);
        bs[i].firstElement = static_cast<uint32_t>(element);
        bs[i].firstParameter = static_cast<uint32_t>(i * p);
        vertex += bs[i].vertexCount;
        element += bs[i].elementCount;
    }
    if (vertex != nv || element != ne)
        return error = "buildings' vertex and element counts sum to " + std::to_string(vertex) + " and " +
                       std::to_string(element) + ", the header says " + std::to_string(nv) + " and " +
                       std::to_string(ne),
               false;
    for (int c = 0; c < 2; ++c)
        r.deltaColumn(nv, [&](size_t i, uint32_t w) { out.footprints[i][c] = fromBits(w); });
    auto& es = out.elements;
    for (int c = 0; c < 3; ++c)
        r.deltaColumn(ne, [&](size_t i, uint32_t w) { es[i].origin[c] = fromBits(w); });
    for (int c = 0; c < 3; ++c) r.column(ne, [&](size_t i, uint32_t w) { es[i].axisX[c] = fromBits(w); });
    for (int c = 0; c < 3; ++c) r.column(ne, [&](size_t i, uint32_t w) { es[i].axisY[c] = fromBits(w); });
    for (int c = 0; c < 2; ++c) r.column(ne, [&](size_t i, uint32_t w) { es[i].size[c] = fromBits(w); });
    r.column(ne, [&](size_t i, uint32_t w) { es[i].rule = w; });
    r.column(ne, [&](size_t i, uint32_t w) { es[i].atom = w; });
    for (size_t j = 0; j < p; ++j)
        r.column(nb, [&](size_t i, uint32_t w) { out.parameters[i * p + j] = fromBits(w); });
    header = info.header;
    set = std::move(out);
    return true;
}

} // namespace hexlod::grammar
