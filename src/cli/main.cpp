// facet: renders OBJ models and scene files to images with the Facet software rasterizer. One file per
// command (render_command, compare_command, bench_command), the options they share in options.h.
#include <iostream>
#include <new>

#include <CLI/CLI.hpp>

#include "base/errors.h"
#include "base/heap.h"
#include "base/memory_limit.h"
#include "cli/bench_command.h"
#include "cli/compare_command.h"
#include "cli/options.h"
#include "cli/render_command.h"
#include "cli/step_command.h"
#include "cli/trade_command.h"
#include "pipeline/thread_pool.h"
#include "render/frame_kernels.h"

#ifndef FACET_VERSION
#error "FACET_VERSION: the project's version, set by src/cli/CMakeLists.txt"
#endif

int main(int argc, char** argv) {
    // Large blocks from the heap, kept after they are freed, and the heap in huge pages where that is
    // free (base/heap.h): loading a model faults in its buffers 2 MB at a time, not 4 KB (the bunny's
    // load and render: docs/performance.md, "End to end").
    facet::setUpHeap();
    // A process limit (ulimit -u, ulimit -v) may refuse some of the threads asked for: the work goes
    // on with those there are, and the user hears it once.
    facet::setThreadShortfallReport([](const std::string& message) {
        std::cerr << "facet: warning: " << message << "\n" << std::flush;
    });
    CLI::App app{"Facet: a software rasterizer. Renders OBJ models and scene files to images on the CPU."};
    app.require_subcommand(1);
    app.set_version_flag("--version", [] {
        std::string text = "facet " FACET_VERSION "\nframe code: ";
        try {
            text += facet::describeFrameKernels();
        } catch (const facet::InputError& e) {
            text += e.what();
        }
        return text;
    });

    facet::cli::RenderArgs renderArgs;
    CLI::App* renderCommand = facet::cli::addRenderCommand(app, renderArgs);
    facet::cli::CompareArgs compareArgs;
    CLI::App* compareCommand = facet::cli::addCompareCommand(app, compareArgs);
    facet::cli::StepArgs stepArgs;
    CLI::App* stepCommand = facet::cli::addStepCommand(app, stepArgs);
    facet::BenchOptions benchOptions;
    CLI::App* benchCommand = facet::cli::addBenchCommand(app, benchOptions);
    facet::cli::TradeArgs tradeArgs;
    CLI::App* tradeCommand = facet::cli::addTradeCommand(app, tradeArgs);

    if (argc == 1) {  // no command at all: show what there is to do
        std::cerr << app.help();
        return 2;
    }
    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForAllHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForVersion& e) {
        return app.exit(e);
    } catch (const CLI::ParseError& e) {
        // One line, like every other error (CLI11's own report adds a second line).
        std::cerr << "facet: error: " << facet::cli::commandLineError(e)
                  << " (facet --help lists the commands and options)\n";
        return 2;
    }

    try {
        // FACET_ISA (src/render/frame_kernels.h) is checked before any work: a bad one is one error,
        // not one per model of a batch.
        facet::frameKernels();
        if (*renderCommand) return facet::cli::render(renderArgs);
        if (*compareCommand) return facet::cli::compare(compareArgs);
        if (*stepCommand) {
            for (int k = 0; k < argc; ++k)
                stepArgs.commandLine += (k ? " " : "") + std::string(k ? argv[k] : "facet");
            return facet::cli::step(stepArgs);
        }
        if (*benchCommand) return facet::cli::bench(benchOptions, *benchCommand);
        if (*tradeCommand) return facet::cli::trade(tradeArgs);
    } catch (const facet::InputError& e) {
        std::cerr << "facet: error: " << e.what() << "\n";
        return facet::kInputErrorExitStatus;
    } catch (const facet::ResourceError& e) {
        std::cerr << "facet: error: " << e.what() << "\n";
        return facet::kResourceExitStatus;
    } catch (const std::bad_alloc&) {
        std::cerr << "facet: error: " << facet::outOfMemoryMessage() << "\n";
        return facet::kResourceExitStatus;
    } catch (const std::exception& e) {
        std::cerr << "facet: internal error: " << e.what() << "\n";
        return 2;
    }
    return 0;
}
