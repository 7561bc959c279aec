#include "disk_tier.h"

#include "hexlod/grammar/terminal_set_codec.h"

#include <algorithm>
#include <chrono>
#include <cstring>
#include <fstream>
#include <string>
#include <vector>

namespace hexlod::cache {

namespace fs = std::filesystem;

namespace {

using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point start) {
    return std::chrono::duration<double>(Clock::now() - start).count();
}

constexpr char kMagic[4] = {'H', 'X', 'C', '1'};
constexpr const char* kExtension = ".hxc";
constexpr const char* kTemporaryExtension = ".tmp";

struct FileHeader {
    BatchKey key;
    uint64_t checksum = 0;
    uint64_t payloadBytes = 0;
};

template <typename T> void put(std::vector<uint8_t>& out, size_t offset, T value) {
    std::memcpy(out.data() + offset, &value, sizeof(T));
}
template <typename T> T get(const uint8_t* in, size_t offset) {
    T value;
    std::memcpy(&value, in + offset, sizeof(T));
    return value;
}

std::vector<uint8_t> writeHeader(const BatchKey& key, uint64_t checksum, uint64_t payloadBytes) {
    std::vector<uint8_t> out(kDiskFileHeaderBytes, 0);
    std::memcpy(out.data(), kMagic, sizeof(kMagic));
    put<uint32_t>(out, 4, kDiskFileVersion);
    put<int32_t>(out, 8, key.cell.q);
    put<int32_t>(out, 12, key.cell.r);
    put<uint32_t>(out, 16, key.grammar);
    put<uint64_t>(out, 24, key.grammarHash);
    put<uint64_t>(out, 32, key.parametersHash);
    put<uint64_t>(out, 40, checksum);
    put<uint64_t>(out, 48, payloadBytes);
    return out;
}

bool readHeader(const uint8_t* bytes, size_t size, FileHeader& header) {
    if (size < kDiskFileHeaderBytes || std::memcmp(bytes, kMagic, sizeof(kMagic)) != 0) return false;
    if (get<uint32_t>(bytes, 4) != kDiskFileVersion || get<uint32_t>(bytes, 20) != 0) return false;
    header.key.cell.q = get<int32_t>(bytes, 8);
    header.key.cell.r = get<int32_t>(bytes, 12);
    header.key.grammar = get<uint32_t>(bytes, 16);
    header.key.grammarHash = get<uint64_t>(bytes, 24);
    header.key.parametersHash = get<uint64_t>(bytes, 32);
    header.checksum = get<uint64_t>(bytes, 40);
    header.payloadBytes = get<uint64_t>(bytes, 48);
    return true;
}

// The digest a cache file name stands for, or nullopt for names the cache did not write.
std::optional<uint64_t> digestOfName(const fs::path& path) {
    const std::string stem = path.stem().string();
    if (path.extension() != kExtension || stem.size() != 16) return std::nullopt;
    uint64_t digest = 0;
    for (char c : stem) {
        const int nibble = c >= '0' && c <= '9' ? c - '0' : c >= 'a' && c <= 'f' ? c - 'a' + 10 : -1;
        if (nibble < 0) return std::nullopt;
        digest = (digest << 4) | uint64_t(nibble);
    }
    return digest;
}

// One read of the whole file into a buffer of its size: set files are megabytes, and growing
// the buffer chunk by chunk copied each one several times over.
std::optional<std::vector<uint8_t>> readFile(const fs::path& path) {
    std::ifstream in(path, std::ios::binary | std::ios::ate);
    if (!in) return std::nullopt;
    const std::streamoff size = in.tellg();
    if (size < 0 || !in.seekg(0)) return std::nullopt;
    std::vector<uint8_t> bytes(static_cast<size_t>(size));
    // A file cut short meanwhile reads as gone; one that grew fails the header's size check.
    if (!in.read(reinterpret_cast<char*>(bytes.data()), size)) return std::nullopt;
    return bytes;
}

} // namespace

DiskTier::DiskTier(fs::path folder, uint64_t budgetBytes, int zstdLevel)
    : folder_(std::move(folder)), budgetBytes_(budgetBytes), zstdLevel_(zstdLevel) {
    fs::create_directories(folder_);
    adoptExisting();
}

fs::path DiskTier::pathOf(uint64_t digest) const {
    return folder_ / (hexDigest(digest) + kExtension);
}

fs::path DiskTier::pathOf(const BatchKey& key) const {
    return pathOf(key.digest());
}

void DiskTier::adoptExisting() {
    struct Found {
        uint64_t digest;
        uint64_t bytes;
        fs::file_time_type used;
    };
    std::vector<Found> found;
    std::error_code ec;
    for (const fs::directory_entry& entry : fs::directory_iterator(folder_, ec)) {
        const fs::path& path = entry.path();
        if (!entry.is_regular_file(ec)) continue;
        if (path.extension() == kTemporaryExtension) { // a write that a crash cut short
            fs::remove(path, ec);
            continue;
        }
        const std::optional<uint64_t> digest = digestOfName(path);
        if (!digest) continue;
        // Only the header is checked here; the payload is checked when it is first read.
        uint8_t bytes[kDiskFileHeaderBytes];
        std::ifstream in(path, std::ios::binary);
        FileHeader header;
        const uint64_t size = entry.file_size(ec);
        const bool valid = in.read(reinterpret_cast<char*>(bytes), sizeof(bytes)) &&
                           readHeader(bytes, sizeof(bytes), header) && header.key.digest() == *digest &&
                           size == kDiskFileHeaderBytes + header.payloadBytes;
        if (!valid) {
            fs::remove(path, ec);
            ++stats_.corruptFilesDropped;
            continue;
        }
        found.push_back({*digest, size, entry.last_write_time(ec)});
    }
    std::sort(found.begin(), found.end(), [](const Found& a, const Found& b) { return a.used < b.used; });
    std::lock_guard lock(mutex_);
    for (const Found& f : found) registerLocked(f.digest, f.bytes);
    evictOverBudgetLocked();
}

void DiskTier::registerLocked(uint64_t digest, uint64_t bytes) {
    auto [it, added] = files_.try_emplace(digest);
    File& file = it->second;
    if (!added) {
        stats_.bytes -= file.bytes;
        lru_.erase(file.lru);
    }
    lru_.push_front(digest);
    file = {bytes, nextGeneration_++, lru_.begin()};
    stats_.bytes += bytes;
    stats_.files = files_.size();
}

void DiskTier::eraseLocked(uint64_t digest, bool unlink) {
    const auto it = files_.find(digest);
    if (it == files_.end()) return;
    stats_.bytes -= it->second.bytes;
    lru_.erase(it->second.lru);
    files_.erase(it);
    stats_.files = files_.size();
    std::error_code ec;
    if (unlink) fs::remove(pathOf(digest), ec);
}

void DiskTier::evictOverBudgetLocked() {
    while (stats_.bytes > budgetBytes_ && !lru_.empty()) {
        eraseLocked(lru_.back(), true);
        ++stats_.evictions;
    }
}

std::optional<grammar::TerminalSet> DiskTier::load(const BatchKey& key) {
    const auto start = Clock::now();
    const uint64_t digest = key.digest();
    uint64_t generation = 0;
    {
        std::lock_guard lock(mutex_);
        const auto it = files_.find(digest);
        if (it == files_.end()) return std::nullopt;
        generation = it->second.generation;
        lru_.splice(lru_.begin(), lru_, it->second.lru);
    }
    // Read and decode without the lock; if the file was replaced meanwhile, the generation
    // check below keeps the new file from being blamed for the old one.
    const std::optional<std::vector<uint8_t>> bytes = readFile(pathOf(digest));
    FileHeader header;
    grammar::TerminalSetPayloadInfo info;
    grammar::TerminalSet set;
    std::string error;
    const bool valid =
        bytes && readHeader(bytes->data(), bytes->size(), header) && header.key == key &&
        header.payloadBytes == bytes->size() - kDiskFileHeaderBytes &&
        grammar::peekTerminalSet(std::span(*bytes).subspan(kDiskFileHeaderBytes), info, error) &&
        info.checksum == header.checksum &&
        grammar::decodeTerminalSet(std::span(*bytes).subspan(kDiskFileHeaderBytes), set, error);
    std::lock_guard lock(mutex_);
    stats_.loadSeconds += secondsSince(start);
    if (valid) return set;
    const auto it = files_.find(digest);
    if (it != files_.end() && it->second.generation == generation) {
        eraseLocked(digest, bytes.has_value()); // a file that vanished is forgotten, not counted
        if (bytes) ++stats_.corruptFilesDropped;
    }
    return std::nullopt;
}

void DiskTier::store(const BatchKey& key, const grammar::TerminalSet& set) {
    const auto start = Clock::now();
    const std::vector<uint8_t> payload = grammar::encodeTerminalSet(set, zstdLevel_);
    grammar::TerminalSetPayloadInfo info;
    std::string error;
    grammar::peekTerminalSet(payload, info, error); // our own encoding: it always parses
    const std::vector<uint8_t> header = writeHeader(key, info.checksum, payload.size());
    uint64_t temporaryId = 0;
    {
        std::lock_guard lock(mutex_);
        temporaryId = nextTemporary_++;
    }
    const fs::path target = pathOf(key);
    const fs::path temporary =
        folder_ / (key.hex() + "." + std::to_string(temporaryId) + kTemporaryExtension);
    bool written = false;
    {
        std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
        out.write(reinterpret_cast<const char*>(header.data()), std::streamsize(header.size()));
        out.write(reinterpret_cast<const char*>(payload.data()), std::streamsize(payload.size()));
        out.close();
        written = !out.fail();
    }
    std::error_code ec;
    std::lock_guard lock(mutex_);
    stats_.storeSeconds += secondsSince(start);
    // The rename happens under the lock so that it is ordered with evictions' unlinks.
    if (written) fs::rename(temporary, target, ec);
    if (!written || ec) {
        fs::remove(temporary, ec);
        ++stats_.writeFailures;
        return;
    }
    registerLocked(key.digest(), header.size() + payload.size());
    evictOverBudgetLocked();
}

void DiskTier::countWriteFailure() {
    std::lock_guard lock(mutex_);
    ++stats_.writeFailures;
}

DiskTierStats DiskTier::stats() const {
    std::lock_guard lock(mutex_);
    return stats_;
}

} // namespace hexlod::cache
