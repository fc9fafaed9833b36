// SPDX-License-Identifier: Apache-2.0
// ms per frame of "ta", "svgf", "bmfr" and (when the build embeds trained weights) the whole "afn"
// filter at 1280x720 on a synthetic moving sequence with warm history (colour, albedo, normal,
// world position, motion); "<method>_passes/N": the same with N light passes denoised with the
// beauty (docs/passes.md; half of them with a colour factor). Run:
//   bench_methods --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
// bench_afn_vs_methods (bench/afn.cmake) links this file with bench_afn.cpp, so that AFN's stages
// and these methods are measured in one run (AFN_BENCH_NO_MAIN leaves out this file's main).
#include "bind_image.h"
#include "filter/registry.h"

#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

namespace {

using afn::Image;
using afntest::bindImage;

constexpr int kWidth = 1280, kHeight = 720;

struct Sequence {
    Image color[2], albedo, normal, position, motion, out;

    Sequence()
    {
        for (int k = 0; k < 2; ++k)
            color[k] = Image(kWidth, kHeight, 3);
        albedo = Image(kWidth, kHeight, 3);
        normal = Image(kWidth, kHeight, 3);
        position = Image(kWidth, kHeight, 3);
        motion = Image(kWidth, kHeight, 2);
        out = Image(kWidth, kHeight, 3);
        std::uint32_t s = 12345u;
        for (int y = 0; y < kHeight; ++y)
            for (int x = 0; x < kWidth; ++x) {
                const bool wall = x > kWidth / 2; // two planes meeting at a crease
                for (int c = 0; c < 3; ++c)
                    albedo(x, y, c) = 0.2f + 0.6f * ((x / 16 + y / 16) % 2);
                normal(x, y, 0) = wall ? -1.0f : 0.0f;
                normal(x, y, 2) = wall ? 0.0f : 1.0f;
                position(x, y, 0) = 0.01f * x;
                position(x, y, 1) = 0.01f * y;
                position(x, y, 2) = wall ? 0.01f * (x - kWidth / 2) : 0.0f;
                motion(x, y, 0) = -0.3f;
                motion(x, y, 1) = 0.2f;
                for (int k = 0; k < 2; ++k)
                    for (int c = 0; c < 3; ++c) {
                        s = s * 1664525u + 1013904223u;
                        const float u = static_cast<float>(s >> 8) / 16777216.0f;
                        color[k](x, y, c)
                            = albedo(x, y, c) * (0.5f + 0.5f * std::sin(0.01f * x)) * 2.0f * u;
                    }
            }
    }
};

void runMethod(benchmark::State& state, const char* method, int passes = 0)
{
    static Sequence seq;
    auto f = afn::createFilter(method);
    // Light passes: each a share of the colour (the first frame's; their noise is not what the
    // timing depends on), every other one with the albedo as its factor.
    std::vector<Image> passIn(static_cast<std::size_t>(passes)), passOut(passIn.size());
    for (int i = 0; i < passes; ++i) {
        passIn[i] = seq.color[0];
        for (std::size_t k = 0; k < passIn[i].size(); ++k)
            passIn[i].data()[k] *= 1.0f / static_cast<float>(passes);
        passOut[i] = Image(kWidth, kHeight, 3);
        const std::string name = "p" + std::to_string(i);
        f->setImage("pass." + name, bindImage(passIn[i]));
        f->setImage("passOutput." + name, bindImage(passOut[i]));
        if (i % 2)
            f->setImage("passFactor." + name, bindImage(seq.albedo));
    }
    f->setImage("albedo", bindImage(seq.albedo));
    f->setImage("normal", bindImage(seq.normal));
    f->setImage("position", bindImage(seq.position));
    f->setImage("motion", bindImage(seq.motion));
    f->setImage("output", bindImage(seq.out));
    int frame = 0;
    auto step = [&] {
        f->setImage("color", bindImage(seq.color[frame++ & 1]));
        f->commit();
        f->execute();
    };
    for (int k = 0; k < 6; ++k)
        step(); // warm history (alpha at its minimum)
    for (auto _ : state) {
        step();
        benchmark::DoNotOptimize(seq.out.data());
    }
    state.SetLabel(std::string(method) + " 1280x720" + (passes ? ", passes" : ""));
}

void BM_svgf_passes(benchmark::State& s)
{
    runMethod(s, "svgf", static_cast<int>(s.range(0)));
}

void BM_afn_passes(benchmark::State& s)
{
    if (!afn::findFilterType("afn")->ready) {
        s.SkipWithError("this build embeds no AFN weights");
        return;
    }
    runMethod(s, "afn", static_cast<int>(s.range(0)));
}

void BM_ta(benchmark::State& s)
{
    runMethod(s, "ta");
}
void BM_svgf(benchmark::State& s)
{
    runMethod(s, "svgf");
}
void BM_bmfr(benchmark::State& s)
{
    runMethod(s, "bmfr");
}

void BM_afn(benchmark::State& s)
{
    if (!afn::findFilterType("afn")->ready) {
        s.SkipWithError("this build embeds no AFN weights");
        return;
    }
    runMethod(s, "afn");
}

BENCHMARK(BM_ta)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_svgf)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_bmfr)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_afn)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_svgf_passes)->Arg(0)->Arg(1)->Arg(8)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_afn_passes)->Arg(0)->Arg(1)->Arg(8)->Unit(benchmark::kMillisecond)->UseRealTime();

} // namespace

#ifndef AFN_BENCH_NO_MAIN
BENCHMARK_MAIN();
#endif
