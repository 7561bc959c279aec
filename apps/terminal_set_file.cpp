#include "terminal_set_file.h"

#include <cstring>
#include <fstream>

namespace hexlod::apps {

bool writeTerminalSetFile(const std::string& path, const grammar::TerminalSet& set, std::string& error) {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    if (!out) {
        error = "cannot open '" + path + "' for writing: " + std::strerror(errno);
        return false;
    }
    const uint32_t version = 1;
    const uint32_t shapes = static_cast<uint32_t>(set.countPerShape.size());
    const uint64_t records = set.records.size();
    out.write("HXTS", 4);
    out.write(reinterpret_cast<const char*>(&version), sizeof(version));
    out.write(reinterpret_cast<const char*>(&set.header), sizeof(set.header));
    out.write(reinterpret_cast<const char*>(&shapes), sizeof(shapes));
    out.write(reinterpret_cast<const char*>(set.countPerShape.data()), shapes * sizeof(uint32_t));
    out.write(reinterpret_cast<const char*>(&records), sizeof(records));
    out.write(reinterpret_cast<const char*>(set.records.data()),
              static_cast<std::streamsize>(records * sizeof(grammar::TerminalRecord)));
    out.close();
    if (!out) {
        error = "failed writing '" + path + "': " + std::strerror(errno);
        return false;
    }
    return true;
}

} // namespace hexlod::apps
