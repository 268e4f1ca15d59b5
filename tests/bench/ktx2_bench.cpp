// Loading one cooked 256^2 cube (RGBA: HDR radiance, distance in alpha) from each file form the
// runtime has read (issue 36: load time of KTX2 against the OpenEXR path it replaced): KTX2
// float32 and half (the runtime's own reader, a copy), KTX2 BC6H with and without decoding to
// floats, and OpenEXR through OpenImageIO (what probes were before format 2). Figures for the
// log; the ratios are read off one run.
#include "engine/image/ktx2.h"
#include "engine/image_io/image_io.h"
#include "tests/support/hdr_test_image.h"

#include <benchmark/benchmark.h>

#include <filesystem>
#include <string>
#include <unistd.h>

using namespace specula;

namespace {

constexpr int kFaceRes = 256;

struct Files {
    std::string dir, f32, f16, bc6h, exr;
    Files() {
        dir = (std::filesystem::temp_directory_path() /
               ("specula-ktx2-bench-" + std::to_string(::getpid())))
                  .string();
        std::filesystem::create_directories(dir);
        const Image rgb = test::hdrTestImage(kFaceRes, 6 * kFaceRes);
        Image cube(kFaceRes, 6 * kFaceRes, 4);
        for (int y = 0; y < cube.height; ++y)
            for (int x = 0; x < cube.width; ++x) {
                std::copy(rgb.at(x, y), rgb.at(x, y) + 3, cube.at(x, y));
                cube.at(x, y)[3] = 1.f + 0.01f * float(x + y); // a distance
            }
        f32 = dir + "/f32.ktx2", f16 = dir + "/f16.ktx2", bc6h = dir + "/bc6h.ktx2";
        exr = dir + "/cube.exr";
        writeKtx2(f32, {.cube = true, .levels = {cube}});
        writeKtx2(f16, {.cube = true, .halfFloat = true, .levels = {cube}});
        writeKtx2(bc6h, {.cube = true, .bc6h = true, .levels = {cube}});
        writeImage(exr, cube);
    }
    ~Files() { std::filesystem::remove_all(dir); }
};

const Files& files() {
    static const Files f;
    return f;
}

void report(benchmark::State& state, const std::string& path) {
    state.SetBytesProcessed(state.iterations() * std::int64_t(std::filesystem::file_size(path)));
    state.counters["file_MiB"] = double(std::filesystem::file_size(path)) / (1024.0 * 1024.0);
}

// Each benchmark reads files() before its loop: the files are written once, untimed.
void BM_ReadKtx2Float32(benchmark::State& state) {
    files();
    for (auto _ : state)
        benchmark::DoNotOptimize(readKtx2(files().f32));
    report(state, files().f32);
}

void BM_ReadKtx2Half(benchmark::State& state) {
    files();
    for (auto _ : state)
        benchmark::DoNotOptimize(readKtx2(files().f16));
    report(state, files().f16);
}

void BM_ReadKtx2Bc6hBlocks(benchmark::State& state) {
    files();
    for (auto _ : state)
        benchmark::DoNotOptimize(readKtx2(files().bc6h, {.decodeBlocks = false}));
    report(state, files().bc6h);
}

void BM_ReadKtx2Bc6hDecoded(benchmark::State& state) {
    files();
    for (auto _ : state)
        benchmark::DoNotOptimize(readKtx2(files().bc6h));
    report(state, files().bc6h);
}

void BM_ReadExrFloat32(benchmark::State& state) {
    files();
    for (auto _ : state)
        benchmark::DoNotOptimize(readFloatExr(files().exr));
    report(state, files().exr);
}

} // namespace

BENCHMARK(BM_ReadKtx2Float32)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ReadKtx2Half)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ReadKtx2Bc6hBlocks)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ReadKtx2Bc6hDecoded)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ReadExrFloat32)->Unit(benchmark::kMillisecond);
BENCHMARK_MAIN();
