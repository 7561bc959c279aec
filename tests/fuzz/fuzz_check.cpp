#include "fuzz_check.h"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <unistd.h>

namespace hexlod::fuzz {

InputFile::InputFile(const uint8_t* data, size_t size, const std::string& extension) {
    // One name per process: libFuzzer runs inputs one after another in a process.
    path_ = (std::filesystem::temp_directory_path() / ("hexlod-fuzz-" + std::to_string(getpid()) + extension))
                .string();
    std::ofstream out(path_, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data), std::streamsize(size));
    check(bool(out));
}

InputFile::~InputFile() {
    std::remove(path_.c_str());
}

} // namespace hexlod::fuzz
