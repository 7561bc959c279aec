// hexlod: streams massive procedural cities with level of detail. Each subcommand lives in
// its own file and registers itself here.
#include "bake_command.h"
#include "bench_error_command.h"
#include "bench_impostors_command.h"
#include "cells_command.h"
#include "expand_command.h"
#include "export_command.h"
#include "import_command.h"
#include "serve_command.h"
#include "walk_command.h"

#include <CLI/CLI.hpp>

#include <iostream>

int main(int argc, char** argv) {
    CLI::App app{"hexlod: massive procedural cities with level of detail"};
    app.require_subcommand(1);
    app.set_version_flag("--version", "hexlod 0.1.0");
    hexlod::apps::ExpandOptions expand;
    CLI::App* expandCommand = hexlod::apps::registerExpandCommand(app, expand);
    hexlod::apps::ImportOptions import;
    CLI::App* importCommand = hexlod::apps::registerImportCommand(app, import);
    hexlod::apps::CellsOptions cells;
    CLI::App* cellsCommand = hexlod::apps::registerCellsCommand(app, cells);
    hexlod::apps::ExportOptions exportOptions;
    CLI::App* exportCommand = hexlod::apps::registerExportCommand(app, exportOptions);
    hexlod::apps::BakeOptions bake;
    CLI::App* bakeCommand = hexlod::apps::registerBakeCommand(app, bake);
    CLI::App* bench = app.add_subcommand("bench", "Benchmarks that print and plot their figures");
    bench->require_subcommand(1);
    hexlod::apps::BenchErrorOptions benchError;
    CLI::App* benchErrorCommand = nullptr;
    hexlod::apps::registerBenchErrorCommand(*bench, benchError, benchErrorCommand);
    hexlod::apps::BenchImpostorsOptions benchImpostors;
    CLI::App* benchImpostorsCommand = nullptr;
    hexlod::apps::registerBenchImpostorsCommand(*bench, benchImpostors, benchImpostorsCommand);
    hexlod::apps::WalkOptions walk;
    CLI::App* walkCommand = hexlod::apps::registerWalkCommand(app, walk);
    hexlod::apps::ServeOptions serve;
    CLI::App* serveCommand = hexlod::apps::registerServeCommand(app, serve);
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        return app.exit(e, std::cout, std::cerr);
    }
    if (expandCommand->parsed()) return hexlod::apps::runExpandCommand(expand);
    if (importCommand->parsed()) return hexlod::apps::runImportCommand(import);
    if (cellsCommand->parsed()) return hexlod::apps::runCellsCommand(cells);
    if (walkCommand->parsed()) return hexlod::apps::runWalkCommand(walk);
    if (bakeCommand->parsed()) return hexlod::apps::runBakeCommand(bake);
    if (benchErrorCommand->parsed()) return hexlod::apps::runBenchErrorCommand(benchError);
    if (benchImpostorsCommand->parsed()) return hexlod::apps::runBenchImpostorsCommand(benchImpostors);
    if (serveCommand->parsed()) return hexlod::apps::runServeCommand(serve);
    if (exportCommand->parsed()) return hexlod::apps::runExportCommand(exportOptions);
    return 0;
}
