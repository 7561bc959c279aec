#include "import_command.h"

#include "hexlod/grammar/compiled_grammar.h"
#include "hexlod/scene/geojson_footprints.h"
#include "hexlod/scene/osm_footprints.h"

#include <nlohmann/json.hpp>

#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <string>
#include <vector>

namespace hexlod::apps {
namespace {

namespace fs = std::filesystem;

constexpr const char* kDefaultGrammar = "residential";

// A shipped grammar by name: configs/grammars/NAME.grammar in the working directory or one of
// its parents, else beside the binary or one of its parents (a build folder sits in the
// checkout). Empty when none exists.
fs::path findShippedGrammar(const std::string& name) {
    const fs::path relative = fs::path("configs") / "grammars" / (name + ".grammar");
    std::error_code ec;
    std::vector<fs::path> starts{fs::current_path(ec)};
    const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
    if (!ec) starts.push_back(exe.parent_path());
    for (fs::path dir : starts) {
        for (; !dir.empty(); dir = dir.parent_path()) {
            if (fs::is_regular_file(dir / relative, ec)) return dir / relative;
            if (dir == dir.parent_path()) break;
        }
    }
    return {};
}

// The grammar file `--grammar` names: a path when it looks like one, else a shipped name.
bool resolveGrammar(const std::string& given, fs::path& path, std::string& error) {
    std::error_code ec;
    if (given.ends_with(".grammar") || given.find('/') != std::string::npos) {
        path = fs::absolute(given, ec);
        if (ec || !fs::is_regular_file(path, ec)) {
            error = "--grammar: no such file '" + given + "'";
            return false;
        }
        return true;
    }
    path = findShippedGrammar(given);
    if (path.empty()) {
        error = "--grammar: no grammar file named '" + given + "' and no configs/grammars/" + given +
                ".grammar found (give a .grammar path)";
        return false;
    }
    return true;
}

// Paths in the config resolve against its folder (docs/scene.md), so they are written
// relative to it; the config can then move together with its data.
std::string relativeTo(const fs::path& target, const fs::path& dir) {
    const fs::path relative = target.lexically_normal().lexically_relative(dir.lexically_normal());
    return relative.empty() ? target.string() : relative.generic_string();
}

// Temp file, then rename: a reader never sees half a config, and a failed write leaves the old one.
bool writeAtomically(const fs::path& path, const std::string& text, std::string& error) {
    const fs::path temp = path.string() + ".tmp-" + std::to_string(::getpid());
    {
        std::ofstream out(temp, std::ios::binary | std::ios::trunc);
        if (out) out << text;
        if (out) out.close();
        if (!out) {
            error = "cannot write '" + path.string() + "': " + std::strerror(errno);
            std::error_code ignored;
            fs::remove(temp, ignored);
            return false;
        }
    }
    std::error_code ec;
    fs::rename(temp, path, ec);
    if (ec) {
        error = "cannot write '" + path.string() + "': " + ec.message();
        fs::remove(temp, ec);
        return false;
    }
    return true;
}

size_t total(const std::map<std::string, size_t>& counts) {
    size_t n = 0;
    for (const auto& entry : counts) n += entry.second;
    return n;
}

} // namespace

CLI::App* registerImportCommand(CLI::App& app, ImportOptions& o) {
    CLI::App* cmd = app.add_subcommand("import", "Import building footprints into a scene config");
    cmd->add_option("input", o.inputPath,
                    "GeoJSON (.geojson, .json) or OpenStreetMap buildings (.osm, .osm.pbf, .osm.bz2)")
        ->required();
    cmd->add_option("-o,--out", o.outPath, "Scene config to write (docs/scene.md)")->required();
    cmd->add_option("--grammar", o.grammar,
                    "Grammar for every building: a .grammar file or a shipped grammar's name (default: " +
                        std::string(kDefaultGrammar) + ")");
    cmd->add_flag("--json", o.json, "Print the counts as one JSON object");
    return cmd;
}

int runImportCommand(const ImportOptions& options) {
    const std::string& input = options.inputPath;
    std::error_code ec;
    if (!fs::is_regular_file(input, ec)) {
        std::cerr << "hexlod import: cannot read '" << input << "': no such file\n";
        return 2;
    }
    const bool geojson = input.ends_with(".geojson") || input.ends_with(".json");
    const bool osm = input.ends_with(".osm") || input.ends_with(".pbf") || input.ends_with(".osm.bz2");
    if (!geojson && !osm) {
        std::cerr << "hexlod import: '" << input
                  << "': unknown footprint format (expected .geojson, .json, .osm, .osm.pbf or .osm.bz2)\n";
        return 2;
    }
    fs::path grammarPath;
    std::string error;
    if (!resolveGrammar(options.grammar.empty() ? kDefaultGrammar : options.grammar, grammarPath, error)) {
        std::cerr << "hexlod import: " << error << "\n";
        return 2;
    }
    grammar::DiagnosticList diagnostics;
    grammar::compileGrammarFile(grammarPath.string(), diagnostics);
    if (diagnostics.hasErrors()) {
        std::cerr << diagnostics.formatAll();
        return 2;
    }

    scene::ImportedFootprints imported;
    const bool read = geojson ? scene::readGeoJsonFootprints(input, imported, error)
                              : scene::readOsmFootprints(input, imported, error);
    if (!read) {
        std::cerr << "hexlod import: " << error << "\n";
        return 1;
    }

    const fs::path out = fs::absolute(options.outPath, ec);
    const fs::path dir = out.parent_path();
    const std::string grammarName = grammarPath.stem().string();
    // Ordered as docs/scene.md presents the fields, for whoever edits the file next.
    const nlohmann::ordered_json config = {
        {"name", out.stem().string()},
        {"grammars", {{grammarName, {{"file", relativeTo(grammarPath, dir)}}}}},
        {"buildings",
         {{{"source", geojson ? "geojson" : "osm"},
           {"path", relativeTo(fs::absolute(input), dir)},
           {"grammar", grammarName}}}},
    };
    if (!writeAtomically(out, config.dump(2) + "\n", error)) {
        std::cerr << "hexlod import: " << error << "\n";
        return 1;
    }

    const size_t skipped = total(imported.skipped);
    if (options.json) {
        const nlohmann::json report = {
            {"buildings", imported.buildings.size()},
            {"skipped", skipped},
            {"skipped_reasons", imported.skipped},
            {"warnings", imported.warnings},
            {"features", imported.features},
            {"holes_ignored", imported.holesIgnored},
            {"grammar", grammarName},
            {"scene", out.string()},
            {"attribution", imported.attribution},
        };
        std::cout << report.dump(2) << "\n";
        return 0;
    }
    std::printf("imported %zu buildings from %zu features of %s, skipped %zu\n", imported.buildings.size(),
                imported.features, input.c_str(), skipped);
    for (const auto& [reason, count] : imported.skipped)
        std::printf("  skipped %zu: %s\n", count, reason.c_str());
    for (const auto& [reason, count] : imported.warnings) {
        std::printf("  kept %zu buildings, ignoring: %s\n", count, reason.c_str());
    }
    if (imported.holesIgnored > 0) {
        std::printf("  ignored %zu inner rings (footprints use outer rings)\n", imported.holesIgnored);
    }
    if (!imported.attribution.empty()) std::printf("  data: %s\n", imported.attribution.c_str());
    std::printf("wrote %s (grammar %s)\n", out.string().c_str(), grammarName.c_str());
    return 0;
}

} // namespace hexlod::apps
