// SPDX-License-Identifier: Apache-2.0
// AFN inference speed per 1280x720 frame (paper Table 10 stages): kernel prediction (padding, tone
// map, encoder-decoder), filtering + fusion (heads, softmax, 7x7 filters, Eq. 3), refinement, and
// the whole forward pass. Random weights of the shipped architecture: timings do not depend on the
// values. Run: afnBenchmarkAfn [--benchmark_filter=...]; report the medians.
#include "methods/afn/network.h"
#include "methods/afn/random_weights.h"

#include <benchmark/benchmark.h>
#include <tbb/global_control.h>

#include <memory>

#include <random>

namespace {

struct Setup {
    afn::Image c1, cta, albedo, normal, depth, out;
    afn::afnet::Network net;
    afn::afnet::Inputs in;

    Setup(int w, int h)
    {
        std::mt19937 rng(1);
        std::uniform_real_distribution<float> u(0.0f, 1.0f);
        auto fill = [&](afn::Image& img, int c, float scale) {
            img = afn::Image(w, h, c);
            for (std::size_t k = 0; k < img.size(); ++k)
                img.data()[k] = scale * u(rng);
        };
        fill(c1, 3, 4.0f);
        fill(cta, 3, 2.0f);
        fill(albedo, 3, 1.0f);
        fill(normal, 3, 1.0f);
        fill(depth, 1, 1.0f);
        net.load(afn::afnet::randomWeights(afn::afnet::Architecture {}));
        in = { &c1, &cta, &albedo, &normal, &depth };
        net.run(in, out); // allocate every buffer once
    }
};

Setup& setup720()
{
    static Setup s(1280, 720);
    return s;
}

// Argument = worker threads (1: the CPU time is the whole cost; 0: all hardware threads).
void configure(benchmark::internal::Benchmark* b)
{
    b->Unit(benchmark::kMillisecond)->Iterations(2)->Repetitions(5)->ReportAggregatesOnly(true);
    b->ArgName("threads")->Arg(1)->Arg(0)->UseRealTime();
}

std::unique_ptr<tbb::global_control> threads(const benchmark::State& state)
{
    if (state.range(0) <= 0)
        return nullptr;
    return std::make_unique<tbb::global_control>(
        tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(state.range(0)));
}

void BM_AfnKernelPrediction(benchmark::State& state)
{
    Setup& s = setup720();
    const auto limit = threads(state);
    for (auto _ : state) {
        s.net.prepare(s.in);
        s.net.predict();
    }
}
BENCHMARK(BM_AfnKernelPrediction)->Name("afn.kernel_prediction.1280x720")->Apply(configure);

void BM_AfnFilterFuse(benchmark::State& state)
{
    Setup& s = setup720();
    const auto limit = threads(state);
    for (auto _ : state)
        s.net.filterAndFuse();
}
BENCHMARK(BM_AfnFilterFuse)->Name("afn.filtering_fusion.1280x720")->Apply(configure);

void BM_AfnRefine(benchmark::State& state)
{
    Setup& s = setup720();
    const auto limit = threads(state);
    for (auto _ : state)
        s.net.refine();
}
BENCHMARK(BM_AfnRefine)->Name("afn.refinement.1280x720")->Apply(configure);

void BM_AfnWhole(benchmark::State& state)
{
    Setup& s = setup720();
    const auto limit = threads(state);
    for (auto _ : state)
        s.net.run(s.in, s.out);
}
BENCHMARK(BM_AfnWhole)->Name("afn.whole.1280x720")->Apply(configure);

} // namespace

BENCHMARK_MAIN();
