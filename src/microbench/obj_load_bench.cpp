// OBJ loading: Facet's own reader against tinyobjloader, its peer, on the Stanford bunny and on Lost
// Empire, the largest OBJ of ../shared/models (a model that is absent is skipped). ReadObj times reading
// the text into attributes and faces (Facet: split, then check and read, on 1 or 2 threads;
// tinyobjloader: LoadObj on the same split text, without the checks Facet adds); LoadObj the whole
// import, MTL files, welding and normals included. Process CPU time counts every thread.
#include <filesystem>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>

#include "io/mtl_reader.h"
#include "io/obj_import.h"
#include "io/obj_scan.h"
#include "io/obj_tinyobj.h"

namespace facet::microbench {
namespace {

namespace fs = std::filesystem;

const fs::path kModels = FACET_SHARED_MODELS;
const fs::path kBunny = kModels / "stanford-bunny" / "stanford-bunny.obj";
const fs::path kLostEmpire = kModels / "lost-empire" / "lost_empire.obj";

void readObjFacet(benchmark::State& state, const fs::path& path, unsigned threads) {
    if (!fs::exists(path)) return state.SkipWithError("model absent");
    const std::string original = obj::readObjText(path, path.string());
    for (auto _ : state) {
        std::string text = original;
        const obj::ObjStatements statements = obj::splitObj(text);
        benchmark::DoNotOptimize(obj::checkObj(text, statements, path.string(), true, threads));
    }
    state.SetBytesProcessed(static_cast<std::int64_t>(state.iterations() * original.size()));
}

void readObjTinyobjloader(benchmark::State& state, const fs::path& path) {
    if (!fs::exists(path)) return state.SkipWithError("model absent");
    const std::string original = obj::readObjText(path, path.string());
    for (auto _ : state) {
        std::string text = original;
        const obj::ObjStatements statements = obj::splitObj(text);  // the text as tinyobjloader gets it
        obj::LibraryReader libraries(path.parent_path());
        std::vector<tinyobj::material_t> materials;
        benchmark::DoNotOptimize(obj::readWithTinyobjloader(text, libraries, materials));
    }
    state.SetBytesProcessed(static_cast<std::int64_t>(state.iterations() * original.size()));
}

void loadObj(benchmark::State& state, const fs::path& path, ObjReader reader) {
    if (!fs::exists(path)) return state.SkipWithError("model absent");
    for (auto _ : state)
        benchmark::DoNotOptimize(loadObjWith(path, reader));
}

BENCHMARK_CAPTURE(readObjFacet, bunny_1_thread, kBunny, 1)
    ->Unit(benchmark::kMillisecond)
    ->MeasureProcessCPUTime();
BENCHMARK_CAPTURE(readObjFacet, bunny_2_threads, kBunny, 2)
    ->Unit(benchmark::kMillisecond)
    ->MeasureProcessCPUTime();
BENCHMARK_CAPTURE(readObjTinyobjloader, bunny, kBunny)
    ->Unit(benchmark::kMillisecond)
    ->MeasureProcessCPUTime();
BENCHMARK_CAPTURE(readObjFacet, lost_empire_1_thread, kLostEmpire, 1)
    ->Unit(benchmark::kMillisecond)
    ->MeasureProcessCPUTime();
BENCHMARK_CAPTURE(readObjFacet, lost_empire_2_threads, kLostEmpire, 2)
    ->Unit(benchmark::kMillisecond)
    ->MeasureProcessCPUTime();
BENCHMARK_CAPTURE(readObjTinyobjloader, lost_empire, kLostEmpire)
    ->Unit(benchmark::kMillisecond)
    ->MeasureProcessCPUTime();
BENCHMARK_CAPTURE(loadObj, bunny_facet, kBunny, ObjReader::kFacet)
    ->Unit(benchmark::kMillisecond)
    ->MeasureProcessCPUTime();
BENCHMARK_CAPTURE(loadObj, bunny_tinyobjloader, kBunny, ObjReader::kTinyobjloader)
    ->Unit(benchmark::kMillisecond)
    ->MeasureProcessCPUTime();
BENCHMARK_CAPTURE(loadObj, lost_empire_facet, kLostEmpire, ObjReader::kFacet)
    ->Unit(benchmark::kMillisecond)
    ->MeasureProcessCPUTime();
BENCHMARK_CAPTURE(loadObj, lost_empire_tinyobjloader, kLostEmpire, ObjReader::kTinyobjloader)
    ->Unit(benchmark::kMillisecond)
    ->MeasureProcessCPUTime();

}  // namespace
}  // namespace facet::microbench
