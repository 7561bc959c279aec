// What every fuzz target uses to report a broken invariant: abort(), which libFuzzer records
// as a crash with the input that caused it, like a sanitizer report.
#pragma once

#include <cmath>
#include <cstdlib>
#include <string>
#include <string_view>

namespace hexlod::fuzz {

inline void check(bool condition) {
    if (!condition) std::abort();
}

inline bool startsWith(std::string_view text, std::string_view prefix) {
    return text.substr(0, prefix.size()) == prefix;
}

template <typename... T> bool allFinite(T... values) {
    return (std::isfinite(double(values)) && ...);
}

// A fresh file under the temporary directory holding `bytes`, for readers that take a path;
// removed when the object goes.
class InputFile {
public:
    InputFile(const uint8_t* data, size_t size, const std::string& extension);
    ~InputFile();
    InputFile(const InputFile&) = delete;
    InputFile& operator=(const InputFile&) = delete;
    const std::string& path() const { return path_; }

private:
    std::string path_;
};

} // namespace hexlod::fuzz
