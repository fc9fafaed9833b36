// SPDX-License-Identifier: Apache-2.0
// AFN inference speed per 1280x720 frame (paper Table 10 stages): kernel prediction (padding, tone
// map, encoder-decoder), filtering + fusion (heads, softmax, 7x7 filters, Eq. 3), refinement (the
// whole-frame stages), the whole forward pass (the stripe path, Network::run), and the whole pass
// with 60 % of the frame masked out by a work mask, the 1-spp post-filter, and single conv layers
// in fp32 and bf16 (nn.conv). Random weights of
// the shipped architecture: timings do not depend on the values. Each case reports GFLOP/s (counter
// "GFLOPs": Network::stageFlop over real time); the yardstick, oneDNN's dnnl_sgemm on 1024^3 at the
// same thread counts, runs in the same program (sgemm.1024, built with oneDNN). Run:
// afnBenchmarkAfn
// [--benchmark_filter=...]; report the medians. The kernels are chosen at run time
// (AFN_CPU_ISA=portable forces the portable ones).
#include "cpu/isa.h"
#include "methods/afn/network.h"
#include "methods/afn/post_filter.h"
#include "methods/afn/random_weights.h"
#include "nn/conv.h"

#include <benchmark/benchmark.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <memory>
#include <random>
#include <vector>

#ifdef AFN_HAS_DNNL
#include "keep_freed_memory_mapped.h" // cli/: the yardstick's scope, shared with afntool

#include <dnnl.h>
#include <omp.h>
#include <thread>
#endif

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
        // The whole-frame stages read each other's results: prediction's decoder features feed
        // the filtering, its fused image the refinement. Run them once here, so that a case run
        // alone (--benchmark_filter) times real work, not a pass over empty images.
        net.prepare(in);
        net.predict();
        net.filterAndFuse();
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

using Stage = afn::afnet::Network::Stage;

void setFlops(benchmark::State& state, double flopPerIteration)
{
    state.counters["GFLOPs"]
        = benchmark::Counter(flopPerIteration * 1e-9 * static_cast<double>(state.iterations()),
            benchmark::Counter::kIsRate);
}

void BM_AfnKernelPrediction(benchmark::State& state)
{
    Setup& s = setup720();
    const auto limit = threads(state);
    for (auto _ : state) {
        s.net.prepare(s.in);
        s.net.predict();
    }
    setFlops(state, s.net.stageFlop(Stage::Prediction));
}
BENCHMARK(BM_AfnKernelPrediction)->Name("afn.kernel_prediction.1280x720")->Apply(configure);

// One 3x3 or 1x1 layer over a 1280x720 image, one thread: the convolution kernels alone (fp32,
// and bf16 with the kernel activeBf16Mode() picks: AMX, VDPBF16PS or its emulation). Arguments:
// input channels, output channels, kernel size, 16 for bf16 (32 for fp32).
void BM_ConvLayer(benchmark::State& state)
{
    const int cin = static_cast<int>(state.range(0)), cout = static_cast<int>(state.range(1));
    const int k = static_cast<int>(state.range(2));
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> u(-0.5f, 0.5f);
    afn::nn::WeightTensor w { { cout, cin, k, k }, {} }, b { { cout }, {} };
    w.data.resize(static_cast<std::size_t>(cout) * cin * k * k);
    b.data.resize(cout);
    for (float& v : w.data)
        v = u(rng);
    for (float& v : b.data)
        v = u(rng);
    const auto archive = afn::nn::WeightsArchive::fromTensors(
        { { "c.weight", w }, { "c.bias", b } }, {}, "benchmark");
    afn::nn::Conv conv;
    conv.load(archive, "c", cin);
    if (state.range(3) == 16)
        conv.setPrecision(afn::nn::Precision::Bf16);
    afn::Image in(1280, 720, cin), out;
    for (std::size_t i = 0; i < in.size(); ++i)
        in.data()[i] = u(rng);
    tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
    for (auto _ : state)
        conv.run(nullptr, in, out, true);
    setFlops(state, conv.flopPerPixel() * 1280.0 * 720.0);
    state.SetLabel(state.range(3) == 16 && conv.precision() == afn::nn::Precision::Bf16
            ? afn::cpu::bf16ModeName(afn::cpu::activeBf16Mode())
            : "fp32");
}
BENCHMARK(BM_ConvLayer)
    ->Name("nn.conv.1280x720")
    ->ArgNames({ "in", "out", "k", "bits" })
    ->Args({ 32, 32, 3, 32 })
    ->Args({ 32, 32, 3, 16 })
    ->Args({ 16, 16, 3, 32 })
    ->Args({ 16, 16, 3, 16 })
    ->Args({ 64, 64, 3, 32 })
    ->Args({ 64, 64, 3, 16 })
    ->Args({ 37, 50, 1, 32 })
    ->Args({ 37, 50, 1, 16 })
    ->Unit(benchmark::kMillisecond)
    ->Iterations(3)
    ->Repetitions(3)
    ->ReportAggregatesOnly(true)
    ->UseRealTime();

void BM_AfnFilterFuse(benchmark::State& state)
{
    Setup& s = setup720();
    const auto limit = threads(state);
    for (auto _ : state)
        s.net.filterAndFuse();
    setFlops(state, s.net.stageFlop(Stage::Filtering));
}
BENCHMARK(BM_AfnFilterFuse)->Name("afn.filtering_fusion.1280x720")->Apply(configure);

void BM_AfnRefine(benchmark::State& state)
{
    Setup& s = setup720();
    const auto limit = threads(state);
    for (auto _ : state)
        s.net.refine();
    setFlops(state, s.net.stageFlop(Stage::Refinement));
}
BENCHMARK(BM_AfnRefine)->Name("afn.refinement.1280x720")->Apply(configure);

void BM_AfnWhole(benchmark::State& state)
{
    Setup& s = setup720();
    const auto limit = threads(state);
    for (auto _ : state)
        s.net.run(s.in, s.out);
    setFlops(state,
        s.net.stageFlop(Stage::Prediction) + s.net.stageFlop(Stage::Filtering)
            + s.net.stageFlop(Stage::Refinement));
}
BENCHMARK(BM_AfnWhole)->Name("afn.whole.1280x720")->Apply(configure);

// Work skipping: the same pass with the top 60 % of the rows masked out (work = 0), so
// the rows there take the cheap path. Compare with afn.whole.1280x720 in the same run; the
// counter is the full frame's GFLOP over the time, an "effective" rate.
void BM_AfnWholeWork40(benchmark::State& state)
{
    Setup& s = setup720();
    const auto limit = threads(state);
    afn::Image work(s.c1.width(), s.c1.height(), 1, 1.0f);
    std::fill(work.data(), work.at(0, s.c1.height() * 60 / 100), 0.0f);
    for (auto _ : state)
        s.net.run(s.in, s.out, &work);
    state.counters["skipped rows"] = s.net.skippedRows();
    setFlops(state,
        s.net.stageFlop(Stage::Prediction) + s.net.stageFlop(Stage::Filtering)
            + s.net.stageFlop(Stage::Refinement));
}
BENCHMARK(BM_AfnWholeWork40)->Name("afn.whole.work40.1280x720")->Apply(configure);

// afn's 1-spp post-filter (methods/afn/post_filter.h) on the random frame, its guides the
// frame's albedo, normal and depth and its noise scale the 1-spp colour with a history of 4:
// guide planes, noise scale and the three separable a-trous passes, the workspace kept across
// iterations as the filter keeps it across frames.
void BM_AfnPostFilter(benchmark::State& state)
{
    Setup& s = setup720();
    const auto limit = threads(state);
    afn::afnet::PostFilterGuides g { &s.albedo, &s.normal, &s.depth };
    const afn::Image history(s.c1.width(), s.c1.height(), 1, 4.0f);
    g.noise.irradiance = &s.c1;
    g.noise.historyLength = &history;
    afn::afnet::PostFilterWorkspace workspace;
    afn::Image out;
    for (auto _ : state)
        afn::afnet::edgeAwarePostFilter(s.cta, g, workspace, out);
}
BENCHMARK(BM_AfnPostFilter)->Name("afn.post_filter.1280x720")->Apply(configure);

#ifdef AFN_HAS_DNNL
// The yardstick: dnnl_sgemm, C = A B with M = N = K = 1024 (oneDNN threads on OpenMP).
void BM_DnnlSgemm(benchmark::State& state)
{
    const int n = 1024;
    const int t = state.range(0) > 0 ? static_cast<int>(state.range(0))
                                     : static_cast<int>(std::thread::hardware_concurrency());
    omp_set_num_threads(t);
    std::vector<float> a(std::size_t(n) * n, 0.5f), b(std::size_t(n) * n, 0.25f),
        c(std::size_t(n) * n);
    const afntool::KeepFreedMemoryMapped keepMapped; // no page faults of oneDNN's scratch per call
    dnnl_sgemm('N', 'N', n, n, n, 1.0f, a.data(), n, b.data(), n, 0.0f, c.data(), n); // warm-up
    for (auto _ : state)
        dnnl_sgemm('N', 'N', n, n, n, 1.0f, a.data(), n, b.data(), n, 0.0f, c.data(), n);
    setFlops(state, 2.0 * n * n * double(n));
}
BENCHMARK(BM_DnnlSgemm)
    ->Name("sgemm.1024")
    ->Unit(benchmark::kMillisecond)
    ->Iterations(10)
    ->Repetitions(5)
    ->ReportAggregatesOnly(true)
    ->ArgName("threads")
    ->Arg(1)
    ->Arg(0)
    ->UseRealTime();
#endif

} // namespace

BENCHMARK_MAIN();
