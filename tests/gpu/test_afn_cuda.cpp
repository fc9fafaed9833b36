// SPDX-License-Identifier: Apache-2.0
// The CUDA afn filter against the CPU afn filter in the same process, frame by frame, on
// synthetic sequences generated here (afn_parity_cases.h: sizes from 1 x 1 to 1280 x 720, each
// input set, the committed test archives and the shipped model). Per frame: the output within the
// documented tolerance (afn_output_compare.h, docs/gpu.md), the first stage (demodulation,
// reprojection, accumulation) equal to the CPU stages', the network input equal to half
// precision. The GPU buffers are poisoned with NaN, so a value no kernel wrote fails the test.
// Also: real renders (the bundled Blender sequence as raw frames), the C API, other methods
// refused, reset and new weights mid-sequence, the model following the inputs across resets,
// concurrent filters.
// Without a usable GPU every test is skipped with the reason.
#include "afn_output_compare.h"
#include "afn_parity_cases.h"
#include "base/device.h"
#include "base/exception.h"
#include "cuda/afn_cuda_filter.h"
#include "cuda/gpu.h"
#include "filter/registry.h"
#include "methods/afn/model_set.h"
#include "methods/afn/network_inputs.h"
#include "methods/afn/tone_map.h"
#include "methods/afn/weights_source.h"
#include "raw_frames.h"
#include "stages/demodulate.h"

#include "afn/afn.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <limits>
#include <memory>
#include <thread>

extern "C" const unsigned char afnTestWeightsFull[];
extern "C" const unsigned long long afnTestWeightsFull_size;
extern "C" const unsigned char afnTestWeightsFusion[];
extern "C" const unsigned long long afnTestWeightsFusion_size;
extern "C" const unsigned char afnTestWeightsTrust[];
extern "C" const unsigned long long afnTestWeightsTrust_size;
extern "C" const unsigned char afnTestWeightsLarge[];
extern "C" const unsigned long long afnTestWeightsLarge_size;
extern "C" const unsigned char afnTestWeightsQuarter[];
extern "C" const unsigned long long afnTestWeightsQuarter_size;

namespace {

using afntest::ParityCase;
using afntest::SequenceInputs;

std::unique_ptr<afn::Device> g_cuda; ///< the CUDA device, when there is a usable GPU
std::string g_noGpu; ///< why there is none

/// Archive bytes of a case's weights; empty for "shipped" (the filters' built-in weights).
std::vector<char> weightsBytes(const std::string& which)
{
    if (which == "full")
        return { afnTestWeightsFull, afnTestWeightsFull + afnTestWeightsFull_size };
    if (which == "fusion")
        return { afnTestWeightsFusion, afnTestWeightsFusion + afnTestWeightsFusion_size };
    if (which == "trust")
        return { afnTestWeightsTrust, afnTestWeightsTrust + afnTestWeightsTrust_size };
    if (which == "large")
        return { afnTestWeightsLarge, afnTestWeightsLarge + afnTestWeightsLarge_size };
    if (which == "quarter")
        return { afnTestWeightsQuarter, afnTestWeightsQuarter + afnTestWeightsQuarter_size };
    return {};
}

/// Whether this build has built-in weights.
bool hasShippedWeights()
{
    afn::afnet::Network net;
    return afn::afnet::loadEmbeddedNetwork(net);
}

afn::cuda::AfnCudaFilter& cudaFilter(afn::Filter& f)
{
    auto* c = dynamic_cast<afn::cuda::AfnCudaFilter*>(&f);
    if (!c)
        throw std::runtime_error("the afn filter on the CUDA device is not the CUDA filter");
    return *c;
}

/// afn on the CPU, configured as the CUDA filter computes (afn_parity_cases.h), and afn on the
/// CUDA device with its buffers poisoned (a value read before it is written shows as NaN).
struct FilterPair {
    std::unique_ptr<afn::Filter> cpu, gpu;
};

FilterPair cpuAndGpuFilters()
{
    FilterPair p { afn::createFilter("afn"), afn::createFilter("afn", *g_cuda) };
    afntest::configureAsOnTheGpu(*p.cpu);
    cudaFilter(*p.gpu).setPoison(true);
    return p;
}

/// The per-frame log's model line of the last frame (AFN_STAT_AFN_MODEL); a failure where the
/// filter has none.
std::string modelLine(const afn::Filter& f)
{
    std::string line;
    if (!f.stringStatistic(AFN_STAT_AFN_MODEL, line))
        ADD_FAILURE() << "the filter reports no " << AFN_STAT_AFN_MODEL;
    return line;
}

void poison(afn::Image& img)
{
    img.fill(std::numeric_limits<float>::quiet_NaN());
}

class CudaAfn : public ::testing::Test {
protected:
    static void SetUpTestSuite()
    {
        if (g_cuda || !g_noGpu.empty())
            return;
        try {
            auto device = std::make_unique<afn::Device>(AFN_DEVICE_TYPE_CUDA);
            device->commit();
            const afn::cuda::GpuInfo gpu = afn::cuda::findGpu();
            std::cout << "[ gpu ] " << gpu.name << ", compute capability " << gpu.major << "."
                      << gpu.minor << ", " << gpu.multiprocessors << " SMs, "
                      << gpu.memoryBytes / (1024 * 1024) << " MiB\n";
            g_cuda = std::move(device);
        } catch (const afn::Exception& e) {
            g_noGpu = e.what();
        }
    }
    void SetUp() override
    {
        if (!g_cuda)
            GTEST_SKIP() << "skipped (" << g_noGpu << ")";
    }
};

/// AFN large's network input from the CPU's inputs (network_large.cpp prepare()): x = [T(c),
/// albedo, normal01, depth01] at the padded size, edge replicated.
afn::Image largeInput(const afn::afnet::Inputs& in)
{
    const int w = in.color1->width(), h = in.color1->height();
    afn::Image x(afn::afnet::paddedSize(w), afn::afnet::paddedSize(h), 10);
    for (int y = 0; y < x.height(); ++y)
        for (int px = 0; px < x.width(); ++px) {
            const int sx = std::min(px, w - 1), sy = std::min(y, h - 1);
            float* o = x.at(px, y);
            for (int k = 0; k < 3; ++k) {
                o[k] = afn::afnet::toneMap(in.color1->at(sx, sy)[k]);
                o[3 + k] = in.albedo->at(sx, sy)[k];
                o[6 + k] = in.normal01->at(sx, sy)[k];
            }
            o[9] = in.depth01->at(sx, sy)[0];
        }
    return x;
}

/// One case: the CPU and CUDA filters side by side, every frame checked.
void runParityCase(const ParityCase& c)
{
    SCOPED_TRACE(c.name());
    const std::vector<char> weights = weightsBytes(c.weights);
    auto [cpu, gpu] = cpuAndGpuFilters();
    afn::cuda::AfnCudaFilter& cuda = cudaFilter(*gpu);
    if (!weights.empty()) {
        cpu->setData(AFN_DATA_WEIGHTS, weights.data(), weights.size());
        gpu->setData(AFN_DATA_WEIGHTS, weights.data(), weights.size());
    }
    for (afn::Filter* f : { cpu.get(), gpu.get() })
        f->params().setNumber("spp", c.spp, AFN_PARAM_INT);
    afn::AuxSettings aux;
    aux.spp = c.spp;
    // The CPU stages and network input, for the intermediates: the model both filters choose for
    // the sequence's inputs (model_set.h).
    afn::afnet::ModelSet models = weights.empty()
        ? afn::afnet::ModelSet::embedded()
        : afn::afnet::ModelSet::fromData(weights.data(), weights.size());
    afn::afnet::Model* model = models.choose(afntest::inputSetOf(c.inputs), c.spp);
    ASSERT_NE(model, nullptr) << "no model for " << c.inputs.name();
    afn::afnet::Network& net = model->net;
    afntest::FrameGatherer gatherer;
    afntest::CpuFirstStage stages(aux, afn::HistoryTrustSettings {});
    afn::afnet::NetworkInputs inputs;
    afn::Image gpuIrr, gpuAcc, gpuX;

    const afntest::SyntheticSequence seq(c.width, c.height, 11);
    afn::Image cpuOut(c.width, c.height, 3), gpuOut(c.width, c.height, 3);
    const afntest::Tolerance tolerance;
    for (int k = 0; k < c.frames; ++k) {
        afntest::SequenceFrame in = seq.frame(k, c.inputs);
        poison(cpuOut);
        poison(gpuOut);
        afntest::runFrame(*cpu, in, cpuOut);
        afntest::runFrame(*gpu, in, gpuOut);

        stages.run(gatherer.gather(in));
        const afn::Frame& f = stages.frame;
        const afn::Image& irradiance = stages.irradiance;
        const afn::TemporalAccumulator& accumulator = stages.accumulator;
        // The model's inputs, history01 where the weights read it.
        inputs.prepare(f, model->inputs, irradiance, accumulator.color(),
            net.hasHistoryInput() ? &accumulator.historyLength() : nullptr);
        const bool large = net.variant() == afn::afnet::Variant::Large;
        const afn::Image expectedX = large ? largeInput(inputs.inputs()) : afn::Image {};
        if (!large)
            net.prepare(inputs.inputs());
        cuda.pipeline().downloadIntermediate(
            afn::cuda::AfnPipeline::Intermediate::Irradiance, gpuIrr);
        cuda.pipeline().downloadIntermediate(
            afn::cuda::AfnPipeline::Intermediate::Accumulated, gpuAcc);
        cuda.pipeline().downloadIntermediate(
            afn::cuda::AfnPipeline::Intermediate::NetworkInput, gpuX);

        const afntest::OutputDifference d = afntest::compareOutputs(gpuOut, cpuOut);
        const double irrDiff = afntest::maxAbsDifference(gpuIrr, irradiance);
        const double taDiff = afntest::maxAbsDifference(gpuAcc, accumulator.color());
        const double xDiff = afntest::maxAbsDifference(gpuX, large ? expectedX : net.input());
        std::cout << "[ parity ] " << c.name() << " frame " << k << ": " << d.text()
                  << "; TA max|diff| " << taDiff << ", irradiance " << irrDiff << ", network input "
                  << xDiff << "\n";
        EXPECT_TRUE(d.within(tolerance)) << "frame " << k << ": " << d.text();
        // The first stage repeats the CPU's arithmetic (temporal_pixel.h): equal up to rounding.
        EXPECT_EQ(irrDiff, 0.0) << "frame " << k;
        EXPECT_LE(taDiff, 1e-5) << "frame " << k;
        // Values in [0, 1] stored as halves (one rounding, possibly on the other side of a tie).
        EXPECT_LE(xDiff, 5e-4) << "frame " << k;
        EXPECT_EQ(modelLine(*gpu), modelLine(*cpu)) << "frame " << k;
    }
}

} // namespace

TEST_F(CudaAfn, ParityWithTheCpuEngine)
{
    const bool shipped = hasShippedWeights();
    for (const ParityCase& c : afntest::gpuParityCases()) {
        if (c.weights == "shipped" && !shipped) {
            std::cout << "[ parity ] " << c.name()
                      << ": no shipped weights the CUDA engine runs in this build\n";
            continue;
        }
        if (c.weights != "shipped" && !afntest::cpuRunsTheFullModel(c.inputs)) {
            std::cout << "[ parity ] " << c.name() << ": one full-input archive, no model\n";
            continue;
        }
        runParityCase(c);
    }
}

// Real renders: the bundled Blender sequence's first frames as raw planes (AFN_GPU_FRAMES, written
// by scripts/dump-gpu-frames.py; scripts/gpu-check.sh sets it for the bundle's frames), the
// default settings (built-in models) on both devices, the CPU's convolutions in fp32.
TEST_F(CudaAfn, ParityOnTheBlenderSequence)
{
    const char* dir = std::getenv("AFN_GPU_FRAMES");
    if (!dir)
        GTEST_SKIP() << "AFN_GPU_FRAMES is not set (scripts/gpu-check.sh sets it)";
    if (!hasShippedWeights())
        GTEST_SKIP() << "this build has no built-in weights";
    auto [cpu, gpu] = cpuAndGpuFilters();
    for (auto* f : { cpu.get(), gpu.get() })
        f->params().setNumber("motion.yUp", 1.0, AFN_PARAM_BOOL);
    const afntest::Tolerance tolerance;
    for (int k = 0; k < 4; ++k) {
        char name[32];
        std::snprintf(name, sizeof name, "/frame.%04d.afnraw", k);
        afntest::SequenceFrame in;
        ASSERT_TRUE(afntest::readRawFrame(std::string(dir) + name, in)) << dir << name;
        afn::Image cpuOut(in.color.width(), in.color.height(), 3), gpuOut = cpuOut;
        poison(cpuOut);
        poison(gpuOut);
        afntest::runFrame(*cpu, in, cpuOut);
        afntest::runFrame(*gpu, in, gpuOut);
        const afntest::OutputDifference d = afntest::compareOutputs(gpuOut, cpuOut);
        std::cout << "[ parity ] examples/sequence frame " << k << ": " << d.text() << "\n";
        EXPECT_TRUE(d.within(tolerance)) << "frame " << k << ": " << d.text();
    }
    // The per-frame log's model line, as the CPU filter's for this full-input frame.
    EXPECT_EQ(modelLine(*gpu), modelLine(*cpu));
}

TEST_F(CudaAfn, OtherMethodsAreUnsupportedOnTheCudaDevice)
{
    for (const char* method : { "identity", "ta", "svgf", "bmfr" }) {
        try {
            afn::createFilter(method, *g_cuda);
            ADD_FAILURE() << method << " was created on the CUDA device";
        } catch (const afn::Exception& e) {
            EXPECT_EQ(e.code(), AFN_ERROR_UNSUPPORTED) << method << ": " << e.what();
        }
    }
}

TEST_F(CudaAfn, ThroughTheCApi)
{
    AFNDevice cuda = afnNewDevice(AFN_DEVICE_TYPE_CUDA);
    ASSERT_NE(cuda, nullptr);
    EXPECT_EQ(afnGetDeviceInt(cuda, "type"), AFN_DEVICE_TYPE_CUDA);
    afnCommitDevice(cuda);
    EXPECT_EQ(afnNewFilter(cuda, "svgf"), nullptr);
    const char* message = nullptr;
    EXPECT_EQ(afnGetDeviceError(cuda, &message), AFN_ERROR_UNSUPPORTED);
    AFNDevice cpu = afnNewDevice(AFN_DEVICE_TYPE_CPU);
    afnCommitDevice(cpu);
    const std::vector<char> weights = weightsBytes("full");
    AFNFilter filters[2] = { afnNewFilter(cpu, "afn"), afnNewFilter(cuda, "afn") };
    ASSERT_NE(filters[1], nullptr);
    const int w = 70, h = 38;
    const afntest::SyntheticSequence seq(w, h, 4);
    afn::Image out[2] = { afn::Image(w, h, 4), afn::Image(w, h, 4) };
    for (AFNFilter f : filters)
        afnSetFilterData(f, AFN_DATA_WEIGHTS, weights.data(), weights.size());
    // As afntest::configureAsOnTheGpu, through the C API.
    afnSetFilterString(filters[0], "precision", "fp32");
    for (int k = 0; k < 3; ++k) {
        afntest::SequenceFrame in = seq.frame(k, SequenceInputs {});
        for (int i = 0; i < 2; ++i) {
            poison(out[i]);
            AFNFilter f = filters[i];
            afnSetFilterImage(
                f, AFN_IMAGE_COLOR, in.color.data(), AFN_FORMAT_FLOAT3, w, h, 0, 0, 0);
            afnSetFilterImage(
                f, AFN_IMAGE_ALBEDO, in.albedo.data(), AFN_FORMAT_FLOAT3, w, h, 0, 0, 0);
            afnSetFilterImage(
                f, AFN_IMAGE_NORMAL, in.normal.data(), AFN_FORMAT_FLOAT3, w, h, 0, 0, 0);
            afnSetFilterImage(f, AFN_IMAGE_DEPTH, in.depth.data(), AFN_FORMAT_FLOAT, w, h, 0, 0, 0);
            afnSetFilterImage(
                f, AFN_IMAGE_MOTION, in.motion.data(), AFN_FORMAT_FLOAT2, w, h, 0, 0, 0);
            // Alpha from the first channel of the albedo, passed through to a FLOAT4 output.
            afnSetFilterImage(
                f, AFN_IMAGE_ALPHA, in.albedo.data(), AFN_FORMAT_FLOAT, w, h, 0, 12, 0);
            afnSetFilterImage(f, AFN_IMAGE_OUTPUT, out[i].data(), AFN_FORMAT_FLOAT4, w, h, 0, 0, 0);
            afnCommitFilter(f);
            afnExecuteFilter(f);
        }
        for (AFNDevice d : { cpu, cuda }) {
            const char* m = nullptr;
            ASSERT_EQ(afnGetDeviceError(d, &m), AFN_ERROR_NONE) << (m ? m : "");
        }
        afn::Image rgb[2];
        for (int i = 0; i < 2; ++i) {
            rgb[i] = afn::Image(w, h, 3);
            for (int y = 0; y < h; ++y)
                for (int x = 0; x < w; ++x) {
                    for (int c = 0; c < 3; ++c)
                        rgb[i](x, y, c) = out[i](x, y, c);
                    EXPECT_EQ(out[i](x, y, 3), in.albedo(x, y, 0)) << "alpha at " << x << "," << y;
                }
        }
        const afntest::OutputDifference d = afntest::compareOutputs(rgb[1], rgb[0]);
        std::cout << "[ api ] frame " << k << ": " << d.text() << "\n";
        EXPECT_TRUE(d.within(afntest::Tolerance {})) << d.text();
    }
    for (AFNFilter f : filters)
        afnReleaseFilter(f);
    afnReleaseDevice(cpu);
    afnReleaseDevice(cuda);
}

TEST_F(CudaAfn, ResetAndNewWeightsMidSequence)
{
    auto [cpu, gpu] = cpuAndGpuFilters();
    const std::vector<char> full = weightsBytes("full"), fusion = weightsBytes("fusion");
    for (auto* f : { cpu.get(), gpu.get() })
        f->setData(AFN_DATA_WEIGHTS, full.data(), full.size());
    const afntest::SyntheticSequence seq(90, 50, 8);
    afn::Image outs[2] = { afn::Image(90, 50, 3), afn::Image(90, 50, 3) };
    for (int k = 0; k < 8; ++k) {
        if (k == 3)
            for (auto* f : { cpu.get(), gpu.get() })
                f->reset();
        if (k == 5)
            for (auto* f : { cpu.get(), gpu.get() })
                f->setData(AFN_DATA_WEIGHTS, fusion.data(), fusion.size());
        afntest::SequenceFrame in = seq.frame(k, SequenceInputs {});
        afntest::runFrame(*cpu, in, outs[0]);
        afntest::runFrame(*gpu, in, outs[1]);
        const afntest::OutputDifference d = afntest::compareOutputs(outs[1], outs[0]);
        std::cout << "[ reset ] frame " << k << ": " << d.text() << "\n";
        EXPECT_TRUE(d.within(afntest::Tolerance {})) << "frame " << k << ": " << d.text();
        EXPECT_EQ(gpu->frameIndex(), cpu->frameIndex());
    }
}

// The built-in models follow the inputs across resets (a new shot with other passes): full, colour
// only, albedo without normal, full again, and the `spp` parameter raised to 64 (the 16-spp model);
// the same model on both devices (the log's model line) and outputs within tolerance.
TEST_F(CudaAfn, TheModelFollowsTheInputsAcrossResets)
{
    if (!hasShippedWeights())
        GTEST_SKIP() << "this build has no built-in weights";
    auto [cpu, gpu] = cpuAndGpuFilters();
    SequenceInputs colorOnly { false, false, false, false, false, false };
    SequenceInputs albedoOnly;
    albedoOnly.normal = false;
    albedoOnly.depth = false;
    const struct {
        SequenceInputs inputs;
        int spp;
    } shots[] = { { SequenceInputs {}, 1 }, { colorOnly, 1 }, { albedoOnly, 1 },
        { SequenceInputs {}, 1 }, { SequenceInputs {}, 64 } };
    const afntest::SyntheticSequence seq(77, 45, 3);
    afn::Image outs[2] = { afn::Image(77, 45, 3), afn::Image(77, 45, 3) };
    for (const auto& shot : shots) {
        for (auto* f : { cpu.get(), gpu.get() }) {
            f->reset();
            f->params().setNumber("spp", shot.spp, AFN_PARAM_INT);
        }
        for (int k = 0; k < 3; ++k) {
            afntest::SequenceFrame in = seq.frame(k, shot.inputs);
            afntest::runFrame(*cpu, in, outs[0]);
            afntest::runFrame(*gpu, in, outs[1]);
            const afntest::OutputDifference d = afntest::compareOutputs(outs[1], outs[0]);
            const std::string cpuModel = modelLine(*cpu);
            std::cout << "[ shots ] " << shot.inputs.name() << " " << shot.spp << " spp frame " << k
                      << " (" << cpuModel << "): " << d.text() << "\n";
            EXPECT_TRUE(d.within(afntest::Tolerance {})) << shot.inputs.name() << " " << d.text();
            EXPECT_EQ(modelLine(*gpu), cpuModel);
        }
    }
}

TEST_F(CudaAfn, ConcurrentFiltersOnOneDeviceGiveTheirSequentialResults)
{
    const std::vector<char> weights = weightsBytes("full");
    const int w = 160, h = 90, frames = 4;
    auto runSequence = [&](unsigned seed, std::vector<afn::Image>& outs) {
        auto f = afn::createFilter("afn", *g_cuda);
        f->setData(AFN_DATA_WEIGHTS, weights.data(), weights.size());
        const afntest::SyntheticSequence seq(w, h, seed);
        for (int k = 0; k < frames; ++k) {
            afntest::SequenceFrame in = seq.frame(k, SequenceInputs {});
            outs[k] = afn::Image(w, h, 3);
            afntest::runFrame(*f, in, outs[k]);
        }
    };
    std::vector<afn::Image> sequential[2], concurrent[2];
    for (int i = 0; i < 2; ++i) {
        sequential[i].resize(frames);
        concurrent[i].resize(frames);
        runSequence(20 + i, sequential[i]);
    }
    std::string errors[2];
    std::thread threads[2];
    for (int i = 0; i < 2; ++i)
        threads[i] = std::thread([&, i] {
            try {
                g_cuda->run([&] { runSequence(20 + i, concurrent[i]); });
            } catch (const std::exception& e) {
                errors[i] = e.what();
            }
        });
    for (auto& t : threads)
        t.join();
    for (int i = 0; i < 2; ++i) {
        ASSERT_TRUE(errors[i].empty()) << errors[i];
        for (int k = 0; k < frames; ++k)
            EXPECT_EQ(afntest::maxAbsDifference(concurrent[i][k], sequential[i][k]), 0.0)
                << "filter " << i << " frame " << k;
    }
}
