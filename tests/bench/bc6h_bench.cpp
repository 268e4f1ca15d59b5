// BC6H encode and decode speed on one 256^2 cube face of synthetic HDR content (issue 36: the
// encoder's speed in MPix/s). Figures for the log, not an assertion; the rate is the
// "items_per_second" column (texels).
#include "engine/image/bc6h.h"
#include "tests/support/hdr_test_image.h"

#include <benchmark/benchmark.h>

using namespace specula;

namespace {

void BM_EncodeBC6H(benchmark::State& state) {
    const int n = int(state.range(0));
    const Image face = test::hdrTestImage(n, n);
    for (auto _ : state)
        benchmark::DoNotOptimize(encodeBC6H(face));
    state.SetItemsProcessed(state.iterations() * std::int64_t(n) * n);
}

void BM_DecodeBC6H(benchmark::State& state) {
    const int n = int(state.range(0));
    const std::vector<std::uint8_t> blocks = encodeBC6H(test::hdrTestImage(n, n));
    for (auto _ : state)
        benchmark::DoNotOptimize(decodeBC6HHalf(blocks, n, n));
    state.SetItemsProcessed(state.iterations() * std::int64_t(n) * n);
}

} // namespace

BENCHMARK(BM_EncodeBC6H)->Arg(256)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_DecodeBC6H)->Arg(256)->Unit(benchmark::kMillisecond);
BENCHMARK_MAIN();
