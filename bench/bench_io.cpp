// SPDX-License-Identifier: Apache-2.0
// Reading and writing a 1280x720 Blender-like multilayer EXR (22 channels, zip) with afn_io.
//
// Run: build/bench/bench_io --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
#include "afn/io.hpp"

#include <benchmark/benchmark.h>

#include <cmath>
#include <ctime>
#include <filesystem>
#include <unistd.h>

namespace {

namespace fs = std::filesystem;
constexpr int kWidth = 1280, kHeight = 720;

/// The 22 channels of a Blender 3.4 file with the denoising data, normal, position, depth and
/// vector passes; colour passes half, the others float, as Blender writes them.
struct Layout {
    std::vector<std::string> channels, types;
    Layout()
    {
        auto add = [&](const std::string& pass, const std::string& comps, const char* type) {
            for (char c : comps) {
                channels.push_back("ViewLayer." + pass + "." + std::string(1, c));
                types.push_back(type);
            }
        };
        add("Combined", "RGBA", "half");
        add("Denoising Albedo", "RGB", "half");
        add("Denoising Normal", "XYZ", "half");
        add("Denoising Depth", "Z", "float");
        add("Normal", "XYZ", "float");
        add("Position", "XYZ", "float");
        add("Depth", "Z", "float");
        add("Vector", "XYZW", "float");
    }
};

/// Smooth fields with a little per-pixel noise, so zip neither collapses nor explodes them.
std::vector<float> makePixels(std::size_t nch)
{
    std::vector<float> px(static_cast<std::size_t>(kWidth) * kHeight * nch);
    unsigned state = 12345u;
    for (std::size_t i = 0; i < px.size(); ++i) {
        state = state * 1664525u + 1013904223u;
        const std::size_t p = i / nch, c = i % nch;
        const float x = static_cast<float>(p % kWidth), y = static_cast<float>(p / kWidth);
        px[i] = std::sin(0.01f * x + 0.3f * c) * std::cos(0.013f * y) + (state >> 8) * 1e-8f;
    }
    return px;
}

struct Fixture {
    Layout layout;
    std::vector<float> pixels = makePixels(layout.channels.size());
    fs::path dir = fs::temp_directory_path() / ("afn_bench_io_" + std::to_string(::getpid()));
    std::string input = (dir / "frame.exr").string();
    Fixture()
    {
        fs::create_directories(dir);
        afn::io::WriteOptions wo;
        wo.attributes["BlenderMultiChannel"] = "Blender V2.55.1 and newer";
        afn::io::writeImageAtomic(
            input, kWidth, kHeight, layout.channels, pixels.data(), wo, layout.types);
    }
    ~Fixture()
    {
        std::error_code ec;
        fs::remove_all(dir, ec);
    }
};

/// CPU time of the whole process (all threads: OpenEXR decompresses and compresses on its own
/// pool), reported per iteration as "proc_cpu_ms": on a shared machine wall time also counts the
/// time spent waiting for a core.
class ProcessCpu {
public:
    explicit ProcessCpu(benchmark::State& state)
        : m_state(state)
        , m_start(std::clock())
    {
    }
    ~ProcessCpu()
    {
        const double ms = 1000.0 * static_cast<double>(std::clock() - m_start) / CLOCKS_PER_SEC;
        m_state.counters["proc_cpu_ms"]
            = benchmark::Counter(ms, benchmark::Counter::kAvgIterations);
    }

private:
    benchmark::State& m_state;
    std::clock_t m_start;
};

Fixture& fixture()
{
    static Fixture f;
    return f;
}

void BM_ReadFrameRoles(benchmark::State& state)
{
    Fixture& f = fixture();
    ProcessCpu cpu(state);
    for (auto _ : state) {
        afn::io::FrameImages img = afn::io::readFrame(f.input);
        benchmark::DoNotOptimize(img.roles.size());
    }
}
BENCHMARK(BM_ReadFrameRoles)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_ReadFrameKeepAll(benchmark::State& state)
{
    Fixture& f = fixture();
    afn::io::ReadOptions ro;
    ro.keepAll = true;
    ProcessCpu cpu(state);
    for (auto _ : state) {
        afn::io::FrameImages img = afn::io::readFrame(f.input, ro);
        benchmark::DoNotOptimize(img.all->pixels.data());
    }
}
BENCHMARK(BM_ReadFrameKeepAll)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_WriteMultilayerZip(benchmark::State& state)
{
    Fixture& f = fixture();
    const std::string out = (f.dir / "out.exr").string();
    ProcessCpu cpu(state);
    for (auto _ : state)
        afn::io::writeImageAtomic(
            out, kWidth, kHeight, f.layout.channels, f.pixels.data(), {}, f.layout.types);
}
BENCHMARK(BM_WriteMultilayerZip)->Unit(benchmark::kMillisecond)->UseRealTime();

} // namespace

BENCHMARK_MAIN();
