#include "cli/bench_command.h"

#include <filesystem>
#include <iostream>
#include <string>

#include "base/errors.h"
#include "bench/batch_bench.h"
#include "cli/options.h"
#include "io/output_path.h"

namespace facet::cli {

namespace {

constexpr int kMaxBenchFrames = 100'000;  // timed frames per measurement
constexpr int kReferenceBenchFrames = 7;  // --reference: a 1-sample reference frame takes about a second

// The repository this program was built in, found from the executable (REPO/build/src/facet): the
// nearest folder above it holding the bundled models/ and, beside it, the shared ../shared/models.
// Empty when the program has been moved out of its build tree.
std::filesystem::path repositoryOfExecutable() {
    std::error_code error;
    const std::filesystem::path executable = std::filesystem::read_symlink("/proc/self/exe", error);
    if (error) return {};
    for (std::filesystem::path folder = executable.parent_path();
         !folder.empty() && folder != folder.root_path(); folder = folder.parent_path())
        if (std::filesystem::is_directory(folder / "models", error) &&
            std::filesystem::is_directory(folder / "../shared/models", error))
            return folder;
    return {};
}

// The benchmark's models when the command line names none: beside the repository the program was
// built in, so that `facet bench` works from any folder; else relative to the working folder.
void chooseDefaultBenchModels(facet::BenchOptions& options, bool modelGiven) {
    const std::filesystem::path bunny = "stanford-bunny/stanford-bunny.obj";
    const std::filesystem::path repository = repositoryOfExecutable();
    if (!repository.empty()) {
        options.sharedModels = (repository / "../shared/models").lexically_normal();
        options.smallModel = repository / "models/spot/spot_triangulated.obj";
        options.ground = repository / "models/fog-and-glass/ground.obj";
    }
    if (modelGiven) return;
    options.model = options.sharedModels / bunny;
    std::error_code error;
    if (!std::filesystem::is_regular_file(options.model, error))
        throw facet::InputError("the default benchmark model " + options.model.string() +
                                " is not there; name a model to time: facet bench MODEL.obj");
}

// Where the benchmark's progress goes: standard error when a table or the chart goes to standard output
// (--csv -), so the two never mix.
std::ostream& reportStream(const facet::BenchOptions& options) {
    return facet::isStandardOutput(options.csv) || facet::isStandardOutput(options.chart) ? std::cerr
                                                                                          : std::cout;
}

}  // namespace

CLI::App* addBenchCommand(CLI::App& app, facet::BenchOptions& options) {
    CLI::App* command = app.add_subcommand("bench", "Time frames of a model (median ms per frame)");
    command->add_option("model", options.model,
                        "Model or scene (default: the Stanford bunny in ../shared/models)");
    command->add_option("--width", options.width, "Image width (default 1920)")->check(kWholeNumber);
    command->add_option("--height", options.height, "Image height (default 1080)")->check(kWholeNumber);
    command->add_option("--frames", options.frames, "Timed frames (default 30)")
        ->check(wholeNumber(1, kMaxBenchFrames));
    command->add_option("--threads", options.threads, "Worker threads (default: one per hardware thread)")
        ->check(wholeNumber(0, 1024));
    command
        ->add_option("--cut-for", options.cutFor,
                     "Cut the frame's work into the items a frame on N threads runs, whatever --threads "
                     "(the image is the same): to count on a small machine what a bigger one would do, "
                     "e.g. under valgrind (default: cut for --threads)")
        ->check(wholeNumber(1, 1024));
    addKnobOption(*command, *facet::sceneKnobNamed("aa"), [&options](const std::string& value) {
        options.antialiasing = parseName<facet::Antialiasing>(value);
    });
    command
        ->add_option_function<std::string>(
            "--shader",
            [&options](const std::string& file) {
                options.shader = facet::ShaderSpec{file, {}};
            },
            "Time the frame drawn with a shader of your own (a C++ file or a .so, as facet render "
            "--shader), frames taking turns with the built-in per-pixel Blinn-Phong's on the same model: "
            "both medians and their ratio")
        ->type_name("FILE");
    command
        ->add_option_function<std::vector<std::string>>(
            "--uniform",
            [&options](const std::vector<std::string>& values) {
                for (const std::string& value : values)
                    options.uniforms.push_back(parseUniform(value));
            },
            "With --shader: set a uniform of the shader, NAME=VALUE (repeat for more)")
        ->type_name("NAME=VALUE");
    command->add_flag("--instruction-sets", options.instructionSets,
                      "Time the frame with each instruction-set copy of its hot path this CPU runs (what "
                      "FACET_ISA chooses among), frames taking turns, and check their images are identical");
    command->add_flag("--vs-mesa", options.vsMesa,
                      "Compare with Mesa llvmpipe (OSMesa, if installed) on fixed scenes and sweeps, "
                      "same thread count");
    command->add_flag("--quick", options.quick,
                      "With --vs-mesa: a shorter sweep and 5 frames (unless --frames), for a smoke run");
    command->add_option("--csv", options.csv,
                        "With --vs-mesa: where the sweeps' CSV goes (default out/bench-scaling.csv); with "
                        "--reference: where its tables go (default out/bench-reference.csv)");
    command->add_option("--chart", options.chart,
                        "With --vs-mesa: where the sweeps' chart goes (default out/bench-scaling.png)");
    command->add_flag("--sort", options.sort,
                      "Time the transparency sorter on a turntable of MODEL (at least 50,000 triangles): "
                      "insertion sort with memory against std::sort, 60 frames per step (unless --frames)");

    command->add_flag("--transparency", options.transparency,
                      "Time the transparency modes (sorted, unsorted, exact) on a turntable of MODEL made "
                      "half transparent");
    command
        ->add_option("--degrees-per-frame", options.degreesPerFrame,
                     "With --transparency: the turntable's step (default 1)")
        ->check(kFiniteNumber);
    command->add_flag(
        "--reference", options.reference,
        "Time the reference renderer (1 and 16 samples, on 1, 2, 4, ... threads up to --threads), "
        "Embree's ray casting "
        "alone, the BVH build, and the rasterizer's cost per shadowing light (ray-cast, maps "
        "of 1024, 2048, 4096); 7 frames (unless --frames), CSV to out/bench-reference.csv "
        "(unless --csv)");
    command->add_flag(
        "--scaling", options.scaling,
        "Time the frames of MODEL (default: the --vs-mesa scenes) on 1, 2, 4, ... threads up to "
        "--threads: speed-up, CPU time per frame and its ratio to one thread's, the serial "
        "fraction of a frame from a trace of the threads' busy time, and Amdahl's prediction "
        "at 16 threads");
    command
        ->add_option("--batch", options.batchList,
                     "Time a list of inputs (as facet render --list reads it) rendered by one process on "
                     "--threads N threads and by N one-thread processes side by side (--shard), in turns: "
                     "inputs per second of each and their ratio; 3 rounds (unless --frames)")
        ->type_name("LIST");
    return command;
}

int bench(facet::BenchOptions& options, const CLI::App& command) {
    if (command.count("--batch")) {
        // Whole renders of the list's inputs: the frame modes' options do not apply.
        for (const char* option : {"model", "--aa", "--shader", "--uniform", "--instruction-sets",
                                   "--vs-mesa", "--quick", "--csv", "--chart", "--sort", "--transparency",
                                   "--degrees-per-frame", "--reference", "--scaling", "--cut-for"})
            if (command.count(option))
                throw facet::InputError(std::string(option) + " does not go with --batch");
        facet::BatchBenchOptions batch;
        batch.list = options.batchList;
        batch.threads = options.threads;
        if (command.count("--frames")) batch.rounds = options.frames;
        if (command.count("--width")) batch.width = options.width;
        if (command.count("--height")) batch.height = options.height;
        facet::runBatchBench(batch, std::cout);
        return 0;
    }
    if (command.count("--cut-for"))
        for (const char* option : {"--shader", "--instruction-sets", "--vs-mesa", "--sort", "--transparency",
                                   "--reference", "--scaling"})
            if (command.count(option))
                throw facet::InputError(std::string("--cut-for does not go with ") + option +
                                        ": it times plain frames");
    chooseDefaultBenchModels(options, command.count("model") > 0);
    // --shader times plain frames against the built-in's; the other modes draw fixed configurations.
    if (command.count("--uniform") && !options.shader)
        throw facet::InputError("--uniform goes with --shader FILE");
    if (options.shader)
        for (const char* option :
             {"--instruction-sets", "--vs-mesa", "--sort", "--transparency", "--reference", "--scaling"})
            if (command.count(option))
                throw facet::InputError(std::string("--shader does not go with ") + option);
    // --aa times plain frames; the other modes draw fixed configurations.
    if (command.count("--aa"))
        for (const char* option : {"--vs-mesa", "--sort", "--transparency", "--reference", "--scaling"})
            if (command.count(option))
                throw facet::InputError(std::string("--aa does not go with ") + option);
    if (options.scaling) {
        for (const char* option : {"--instruction-sets", "--vs-mesa", "--quick", "--csv", "--chart", "--sort",
                                   "--transparency", "--degrees-per-frame", "--reference"})
            if (command.count(option))
                throw facet::InputError(std::string(option) + " does not go with --scaling");
        if (command.count("model") == 0 && (command.count("--width") || command.count("--height")))
            throw facet::InputError(
                "--scaling renders the --vs-mesa scenes at fixed sizes unless a model is named; "
                "--width and --height go with a model");
        checkSize(options.width, options.height);
        facet::runScalingBench(options, command.count("model") > 0, std::cout);
        return 0;
    }
    if (options.instructionSets) {
        for (const char* option : {"--vs-mesa", "--quick", "--csv", "--chart", "--sort", "--transparency",
                                   "--degrees-per-frame", "--reference"})
            if (command.count(option))
                throw facet::InputError(std::string(option) + " does not go with --instruction-sets");
        checkSize(options.width, options.height);
        facet::runInstructionSetBench(options, std::cout);
        return 0;
    }
    if (options.reference) {
        // --threads sets the rasterizer's threads; the reference and the rays run on 1, 2, 4, ... up to it.
        for (const char* option :
             {"--vs-mesa", "--quick", "--chart", "--sort", "--transparency", "--degrees-per-frame"})
            if (command.count(option))
                throw facet::InputError(std::string(option) + " does not go with --reference");
        if (command.count("--frames") == 0) options.frames = kReferenceBenchFrames;
        if (command.count("--csv") == 0) options.csv = "out/bench-reference.csv";
        checkSize(options.width, options.height);
        facet::runReferenceBench(options, reportStream(options));
        return 0;
    }
    if (options.transparency) {
        for (const char* option : {"--vs-mesa", "--quick", "--csv", "--chart", "--sort"})
            if (command.count(option))
                throw facet::InputError(std::string(option) + " does not go with --transparency");
        checkSize(options.width, options.height);
        facet::runTransparencyBench(options, std::cout);
        return 0;
    }
    if (command.count("--degrees-per-frame"))
        throw facet::InputError("--degrees-per-frame goes with --transparency");
    if (options.sort) {
        // The camera frames MODEL as facet render does; the sort runs on one thread.
        for (const char* option :
             {"--vs-mesa", "--quick", "--csv", "--chart", "--width", "--height", "--threads"})
            if (command.count(option))
                throw facet::InputError(std::string(option) + " does not go with --sort");
        if (command.count("--frames") == 0) options.frames = 60;
        facet::runSortBench(options, std::cout);
        return 0;
    }
    if (options.vsMesa) {
        // The scenes and their sizes are fixed; MODEL replaces the bunny.
        if (command.count("--width") || command.count("--height"))
            throw facet::InputError("--vs-mesa renders fixed sizes; --width and --height do not apply");
        if (options.quick && command.count("--frames") == 0) options.frames = 5;
        facet::runMesaComparison(options, reportStream(options));
        return 0;
    }
    if (options.quick || command.count("--csv") || command.count("--chart"))
        throw facet::InputError("--quick and --chart go with --vs-mesa, --csv with --vs-mesa or --reference");
    checkSize(options.width, options.height);
    facet::runBench(options, std::cout);
    return 0;
}

}  // namespace facet::cli
