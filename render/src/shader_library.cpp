// Include expansion and log mapping for GLSL. GLSL has no #include of its own; #line with a
// source-string number is what lets the compiler's messages point back to the right file.
#include "hexlod/render/shader_library.h"

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <regex>
#include <sstream>

namespace hexlod::render {
namespace {

constexpr int kMaxIncludeDepth = 16;

// `#include "name"` at the start of a line (leading blanks allowed): the name, or empty.
std::string includedName(std::string_view line) {
    size_t at = line.find_first_not_of(" \t");
    if (at == std::string_view::npos || line.compare(at, 8, "#include") != 0) return {};
    size_t open = line.find('"', at + 8);
    size_t close = open == std::string_view::npos ? open : line.find('"', open + 1);
    if (close == std::string_view::npos) return {};
    return std::string(line.substr(open + 1, close - open - 1));
}

bool isVersionLine(std::string_view line) {
    size_t at = line.find_first_not_of(" \t");
    return at != std::string_view::npos && line.compare(at, 8, "#version") == 0;
}

std::string readFromOverrideDir(std::string_view name) {
    const char* dir = std::getenv("HEXLOD_SHADER_DIR");
    if (!dir || !*dir) return {};
    std::ifstream in(std::string(dir) + "/" + std::string(name), std::ios::binary);
    if (!in) return {};
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
}

} // namespace

void ShaderLibrary::add(std::span<const ShaderFile> files) {
    for (const ShaderFile& file : files) files_[std::string(file.name)] = std::string(file.text);
}

void ShaderLibrary::add(std::string name, std::string text) {
    files_[std::move(name)] = std::move(text);
}

bool ShaderLibrary::contains(std::string_view name) const {
    return text(name) != nullptr;
}

const std::string* ShaderLibrary::text(std::string_view name) const {
    auto found = files_.find(std::string(name));
    return found == files_.end() ? nullptr : &found->second;
}

bool ShaderLibrary::expand(std::string_view name, std::string_view defines, ExpandedShader& out,
                           std::string& error) const {
    out = {};
    // Expand into a scratch copy of the library so HEXLOD_SHADER_DIR overrides apply to
    // included files as well.
    ShaderLibrary withOverrides;
    const ShaderLibrary* library = this;
    if (std::getenv("HEXLOD_SHADER_DIR")) {
        withOverrides = *this;
        for (auto& [file, text] : withOverrides.files_) {
            if (std::string fresh = readFromOverrideDir(file); !fresh.empty()) text = std::move(fresh);
        }
        library = &withOverrides;
    }
    if (!library->expandInto(std::string(name), 0, out, error)) return false;
    // The defines go after the #version line, which expandInto leaves first.
    size_t versionEnd = out.text.find('\n');
    if (!isVersionLine(out.text) || versionEnd == std::string::npos) {
        error = std::string(name) + ":1: the first line must be #version";
        return false;
    }
    if (!defines.empty()) {
        std::string block(defines);
        if (block.back() != '\n') block += '\n';
        block += "#line 2 0\n";
        out.text.insert(versionEnd + 1, block);
    }
    return true;
}

bool ShaderLibrary::expandInto(const std::string& name, int depth, ExpandedShader& out,
                               std::string& error) const {
    const std::string* source = text(name);
    if (!source) {
        error = name + ": no such shader";
        return false;
    }
    if (depth > kMaxIncludeDepth) {
        error = name + ": includes nest deeper than " + std::to_string(kMaxIncludeDepth) + " (a cycle?)";
        return false;
    }
    int number = int(out.sourceNames.size());
    out.sourceNames.push_back(name);
    std::istringstream lines(*source);
    std::string line;
    for (int lineNumber = 1; std::getline(lines, line); ++lineNumber) {
        std::string include = includedName(line);
        if (include.empty()) {
            out.text += line;
            out.text += '\n';
            if (depth == 0 && lineNumber == 1 && isVersionLine(line)) out.text += "#line 2 0\n";
            continue;
        }
        if (std::find(out.sourceNames.begin(), out.sourceNames.end(), include) == out.sourceNames.end()) {
            if (!text(include)) {
                error = name + ":" + std::to_string(lineNumber) + ": cannot include \"" + include +
                        "\": no such shader";
                return false;
            }
            out.text += "#line 1 " + std::to_string(out.sourceNames.size()) + "\n";
            if (!expandInto(include, depth + 1, out, error)) return false;
        }
        out.text += "#line " + std::to_string(lineNumber + 1) + " " + std::to_string(number) + "\n";
    }
    return true;
}

std::string ShaderLibrary::mapLog(std::string_view log, const ExpandedShader& shader) {
    // Mesa: "0:12(5): error: ..."; NVIDIA: "0(12) : error C1008: ...".
    static const std::regex location(R"(^(\d+)(?::(\d+)\(\d+\)|\((\d+)\))\s*:\s*)");
    std::istringstream lines{std::string(log)};
    std::string line, mapped;
    while (std::getline(lines, line)) {
        std::smatch match;
        if (std::regex_search(line, match, location)) {
            size_t number = std::strtoul(match[1].str().c_str(), nullptr, 10);
            std::string lineNumber = match[2].matched ? match[2].str() : match[3].str();
            std::string file = number < shader.sourceNames.size() ? shader.sourceNames[number] : "?";
            mapped += file + ":" + lineNumber + ": " + match.suffix().str() + "\n";
        } else if (!line.empty()) {
            mapped += line + "\n";
        }
    }
    return mapped;
}

} // namespace hexlod::render
