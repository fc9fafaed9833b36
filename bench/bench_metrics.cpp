// SPDX-License-Identifier: Apache-2.0
// Speed of the metrics through the public C API: afnComputeMetrics (PSNR, SSIM x2, RMSE, SMAPE)
// and afnComputeTemporalMetrics on 720p and 1080p RGB frames. Reports msec per frame.
#include "afn/afn.hpp"

#include <benchmark/benchmark.h>

#include <cstdint>
#include <vector>

namespace {

std::vector<float> frame(int w, int h, std::uint32_t seed)
{
    std::vector<float> v(static_cast<size_t>(w) * h * 3);
    std::uint32_t s = seed;
    for (float& x : v) {
        s = s * 1664525u + 1013904223u;
        x = 2.0f * static_cast<float>(s >> 8) / 16777216.0f;
    }
    return v;
}

void metricsCase(benchmark::State& state, bool temporal)
{
    const int w = static_cast<int>(state.range(0)), h = static_cast<int>(state.range(1));
    const std::vector<float> a = frame(w, h, 1), b = frame(w, h, 2);
    afn::DeviceRef device = afn::newDevice();
    device.commit();
    AFNMetrics m {};
    AFNTemporalMetrics t {};
    for (auto _ : state) {
        const bool ok = temporal ? afn::computeTemporalMetrics(
                            device, a.data(), b.data(), b.data(), a.data(), w, h, 3, t)
                                 : afn::computeMetrics(device, a.data(), b.data(), w, h, 3, m);
        if (!ok)
            state.SkipWithError("metrics failed");
        benchmark::DoNotOptimize(m);
        benchmark::DoNotOptimize(t);
    }
    state.counters["Mpix/s"] = benchmark::Counter(
        static_cast<double>(w) * h * state.iterations() / 1e6, benchmark::Counter::kIsRate);
}

void BM_Metrics(benchmark::State& s)
{
    metricsCase(s, false);
}
void BM_TemporalMetrics(benchmark::State& s)
{
    metricsCase(s, true);
}

} // namespace

BENCHMARK(BM_Metrics)
    ->Name("metrics.frame")
    ->Args({ 1280, 720 })
    ->Args({ 1920, 1080 })
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_TemporalMetrics)
    ->Name("metrics.temporal")
    ->Args({ 1280, 720 })
    ->Args({ 1920, 1080 })
    ->Unit(benchmark::kMillisecond);
BENCHMARK_MAIN();
