#include "terminal_set_file.h"

#include "hexlod/grammar/terminal_set_codec.h"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>

namespace hexlod::apps {

bool writeTerminalSetFile(const std::string& path, const grammar::TerminalSet& set, std::string& error) {
    const std::vector<uint8_t> bytes = grammar::encodeTerminalSet(set);
    const std::string temporary = path + ".partial";
    {
        std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
        if (!out) {
            error = "cannot open '" + path + "' for writing: " + std::strerror(errno);
            return false;
        }
        out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
        if (!out.flush()) {
            error = "failed writing '" + path + "': " + std::strerror(errno);
            std::remove(temporary.c_str());
            return false;
        }
    }
    if (std::rename(temporary.c_str(), path.c_str()) != 0) {
        error = "cannot replace '" + path + "': " + std::strerror(errno);
        std::remove(temporary.c_str());
        return false;
    }
    return true;
}

} // namespace hexlod::apps
