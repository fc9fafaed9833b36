// SPDX-License-Identifier: Apache-2.0
// Speed of the CUDA afn filter (docs/gpu.md): milliseconds per frame at 1280x720, 1920x1080 and
// 3840x2160 for the whole per-frame graph and for each stage (TA + features, kernel prediction,
// filtering + fusion, refinement), each captured as its own graph; timed with CUDA events over
// batches of back-to-back graph replays (median of the batches' per-frame times). Upload and
// download of a frame are timed apart, and so is a whole afnExecuteFilter-equivalent call (gather
// on the CPU, upload, graph, download, output write; wall clock). Inputs: a synthetic sequence
// with every AOV (second frame, so the history is in use); weights: the shipped model when built
// in, else random weights of its architecture; AFN large's whole graph too where it is built in
// (the model chosen at 64 spp).
//
// Usage: bench_afn_cuda [--sizes 1280x720,1920x1080,3840x2160] [--csv FILE]
// Exit status: 0 done, 1 error, 77 no usable GPU (nothing measured).
#include "afn_synthetic_sequence.h"
#include "base/device.h"
#include "base/exception.h"
#include "cuda/afn_pipeline.h"
#include "cuda/frame_constants.h"
#include "cuda/gpu.h"
#include "filter/registry.h"
#include "methods/afn/model_set.h"
#include "methods/afn/random_weights.h"
#include "methods/afn/settings.h"
#include "methods/afn/weights_source.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <functional>
#include <iostream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

namespace {

using afn::cuda::AfnPipeline;

struct Stat {
    double median = 0.0, min = 0.0, max = 0.0;
};

Stat statOf(std::vector<double> v)
{
    std::sort(v.begin(), v.end());
    Stat s;
    s.median = v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
    s.min = v.front();
    s.max = v.back();
    return s;
}

/// CUDA events around batches of `perBatch` calls of `enqueue`: per-call milliseconds, median
/// over `batches` batches (after one warm-up batch).
Stat timeOnStream(
    cudaStream_t stream, int batches, int perBatch, const std::function<void()>& enqueue)
{
    cudaEvent_t start = nullptr, stop = nullptr;
    AFN_CUDA_CHECK(cudaEventCreate(&start));
    AFN_CUDA_CHECK(cudaEventCreate(&stop));
    std::vector<double> ms;
    for (int b = -1; b < batches; ++b) {
        AFN_CUDA_CHECK(cudaEventRecord(start, stream));
        for (int i = 0; i < perBatch; ++i)
            enqueue();
        AFN_CUDA_CHECK(cudaEventRecord(stop, stream));
        AFN_CUDA_CHECK(cudaEventSynchronize(stop));
        float elapsed = 0.0f;
        AFN_CUDA_CHECK(cudaEventElapsedTime(&elapsed, start, stop));
        if (b >= 0)
            ms.push_back(static_cast<double>(elapsed) / perBatch);
    }
    cudaEventDestroy(start);
    cudaEventDestroy(stop);
    return statOf(ms);
}

/// Wall-clock milliseconds of `call` (which must wait for its own work), median of `repeats`.
Stat timeWall(int repeats, const std::function<void()>& call)
{
    call(); // warm-up
    std::vector<double> ms;
    for (int i = 0; i < repeats; ++i) {
        const auto t0 = std::chrono::steady_clock::now();
        call();
        ms.push_back(
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0)
                .count());
    }
    return statOf(ms);
}

struct Row {
    std::string size, what;
    Stat ms;
    std::string note;
};

bool allFinite(const afn::Image& img)
{
    for (std::size_t i = 0; i < img.size(); ++i)
        if (!std::isfinite(img.data()[i]))
            return false;
    return true;
}

void benchmarkSize(const afn::Device& device, const afn::afnet::Network& net,
    const afn::afnet::Network* large, bool hasBuiltInWeights, int w, int h, std::vector<Row>& rows)
{
    const std::string size = std::to_string(w) + "x" + std::to_string(h);
    const long long pixels = static_cast<long long>(w) * h;
    const int perBatch = pixels > 4000000 ? 5 : 20;
    const int batches = 9;
    std::cout << "bench_afn_cuda: " << size << ": generating inputs..." << std::endl;
    const afntest::SyntheticSequence seq(w, h, 3);
    afntest::SequenceInputs inputs; // every AOV, motion vectors
    afntest::SequenceFrame in[2] = { seq.frame(0, inputs), seq.frame(1, inputs) };

    // The pipeline directly: two frames, so that the timed frame reprojects a history.
    AfnPipeline pipe(device.gpuOrdinal());
    pipe.setNetwork(net);
    // As the filter's taa=auto and postFilter=auto (afn_cuda_filter.cpp).
    pipe.setTaa(net.trainedSpp() < afn::afnet::kTaaAutoMaxSppExclusive);
    pipe.setPostFilter(net.trainedSpp() < afn::afnet::kPostFilterAutoMaxSppExclusive);
    afntest::FrameGatherer gatherer;
    const afn::ReprojectSettings reproject {};
    const afn::AccumulationSettings accumulation {};
    const afn::HistoryTrustSettings trust {}; // the default, antilag 1
    const afn::AuxSettings aux {}; // the default, auto
    afn::Image out;
    for (int k = 0; k < 2; ++k) {
        const afn::Frame& f = gatherer.gather(in[k]);
        pipe.run(f, afn::cuda::frameConstants(f, reproject, accumulation, trust, aux), out);
    }
    const afn::Frame& frame = gatherer.frame; // the second frame, as gathered
    const afn::cuda::FrameConstants constants
        = afn::cuda::frameConstants(frame, reproject, accumulation, trust, aux);
    pipe.configure(frame);
    pipe.upload(frame, constants);
    const cudaStream_t stream = pipe.stream();
    AFN_CUDA_CHECK(cudaStreamSynchronize(stream));

    const struct {
        AfnPipeline::Stage stage;
        const char* name;
    } stages[] = { { AfnPipeline::Stage::TemporalFeatures, "aux + TA + features" },
        { AfnPipeline::Stage::KernelPrediction, "kernel prediction" },
        { AfnPipeline::Stage::FilteringFusion, "filtering + fusion" },
        { AfnPipeline::Stage::Refinement, "refinement" }, { AfnPipeline::Stage::Taa, "TAA" },
        { AfnPipeline::Stage::PostFilter, "post-filter" } };
    for (const auto& s : stages) {
        afn::cuda::GraphExec exec;
        exec.reset(
            afn::cuda::captureGraph(stream, [&](cudaStream_t st) { pipe.enqueue(s.stage, st); }));
        rows.push_back({ size, s.name,
            timeOnStream(stream, batches, perBatch,
                [&] { AFN_CUDA_CHECK(cudaGraphLaunch(exec.get(), stream)); }),
            "graph replays, CUDA events" });
    }
    rows.push_back({ size, "whole filter (graph)",
        timeOnStream(stream, batches, perBatch, [&] { pipe.launch(); }),
        "the per-frame graph, CUDA events" });
    const double upMB = pipe.uploadBytes() / 1e6, downMB = pipe.downloadBytes() / 1e6;
    std::ostringstream up, down;
    up.precision(4);
    down.precision(4);
    const Stat upload = timeWall(batches, [&] {
        pipe.upload(frame, constants);
        AFN_CUDA_CHECK(cudaStreamSynchronize(stream));
    });
    up << upMB << " MB from pageable memory, " << upMB / upload.median << " GB/s, wall clock";
    rows.push_back({ size, "upload", upload, up.str() });
    const Stat download = timeWall(batches, [&] { pipe.download(out); });
    down << downMB << " MB to pageable memory, " << downMB / download.median << " GB/s, wall clock";
    rows.push_back({ size, "download", download, down.str() });
    if (!allFinite(out))
        throw std::runtime_error("the output of " + size + " has NaN or Inf values");

    // AFN large (the built-in model from about 45 spp on), the whole per-frame graph.
    if (large) {
        AfnPipeline largePipe(device.gpuOrdinal());
        largePipe.setNetwork(*large); // taa=auto and postFilter=auto are off at its 64 spp
        afn::AuxSettings largeAux;
        largeAux.spp = 64;
        afntest::FrameGatherer largeGatherer;
        for (int k = 0; k < 2; ++k) {
            const afn::Frame& f = largeGatherer.gather(in[k]);
            largePipe.run(
                f, afn::cuda::frameConstants(f, reproject, accumulation, trust, largeAux), out);
        }
        rows.push_back({ size, "AFN large (graph)",
            timeOnStream(largePipe.stream(), batches, perBatch, [&] { largePipe.launch(); }),
            "the per-frame graph of the 64-spp model, CUDA events" });
        if (!allFinite(out))
            throw std::runtime_error("the AFN large output of " + size + " has NaN or Inf");
    }

    // The whole filter as the API runs it (needs the built-in weights).
    if (!hasBuiltInWeights)
        return;
    auto filter = afn::createFilter("afn", device);
    afn::Image filterOut(w, h, 3);
    int k = 0;
    const Stat execute = timeWall(pixels > 4000000 ? 5 : batches,
        [&] { afntest::runFrame(*filter, in[k++ % 2], filterOut); });
    rows.push_back({ size, "execute (whole call)", execute,
        "gather on the CPU + upload + graph + download + output, wall clock" });
    if (!allFinite(filterOut))
        throw std::runtime_error("the filter output of " + size + " has NaN or Inf values");
}

std::vector<std::pair<int, int>> parseSizes(const std::string& text)
{
    std::vector<std::pair<int, int>> sizes;
    std::stringstream ss(text);
    std::string item;
    while (std::getline(ss, item, ',')) {
        const std::size_t x = item.find('x');
        if (x == std::string::npos)
            throw std::runtime_error("bad size '" + item + "' (expected WxH)");
        sizes.emplace_back(std::stoi(item.substr(0, x)), std::stoi(item.substr(x + 1)));
    }
    return sizes;
}

} // namespace

int main(int argc, char** argv)
{
    std::string sizesText = "1280x720,1920x1080,3840x2160", csv;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        if (a == "--sizes" && i + 1 < argc)
            sizesText = argv[++i];
        else if (a == "--csv" && i + 1 < argc)
            csv = argv[++i];
        else {
            std::cerr << "usage: bench_afn_cuda [--sizes WxH,...] [--csv FILE]\n";
            return 1;
        }
    }
    std::unique_ptr<afn::Device> device;
    try {
        device = std::make_unique<afn::Device>(AFN_DEVICE_TYPE_CUDA);
        device->commit();
    } catch (const afn::Exception& e) {
        std::cout << "bench_afn_cuda: skipped: " << e.what() << "\n";
        return 77;
    }
    try {
        const afn::cuda::GpuInfo gpu = afn::cuda::findGpu();
        std::cout << "bench_afn_cuda: " << gpu.name << ", compute capability " << gpu.major << "."
                  << gpu.minor << ", " << gpu.multiprocessors << " SMs\n";
        afn::afnet::Network net;
        const bool builtIn = afn::afnet::loadEmbeddedNetwork(net);
        if (builtIn) {
            std::cout << "bench_afn_cuda: weights: the shipped model (built in)\n";
        } else {
            net.load(afn::afnet::randomWeights(afn::afnet::Architecture {}));
            std::cout << "bench_afn_cuda: weights: random, the shipped architecture\n";
        }
        // AFN large: the built-in model the filter chooses at 64 spp, when it is one.
        afn::afnet::ModelSet models = afn::afnet::ModelSet::embedded();
        const afn::afnet::Model* m = models.choose(afn::afnet::InputSet::full(), 64);
        const afn::afnet::Network* large
            = m && m->net.variant() == afn::afnet::Variant::Large ? &m->net : nullptr;
        std::vector<Row> rows;
        for (const auto& [w, h] : parseSizes(sizesText))
            benchmarkSize(*device, net, large, builtIn, w, h, rows);

        std::printf("\n%-10s  %-22s %9s %9s %9s  %s\n", "size", "what", "median", "min", "max",
            "how (milliseconds per frame)");
        for (const Row& r : rows)
            std::printf("%-10s  %-22s %9.3f %9.3f %9.3f  %s\n", r.size.c_str(), r.what.c_str(),
                r.ms.median, r.ms.min, r.ms.max, r.note.c_str());
        if (!csv.empty()) {
            std::ofstream f(csv);
            f << "size,what,median_ms,min_ms,max_ms,how\n";
            for (const Row& r : rows)
                f << r.size << "," << r.what << "," << r.ms.median << "," << r.ms.min << ","
                  << r.ms.max << ",\"" << r.note << "\"\n";
        }
        return 0;
    } catch (const std::exception& e) {
        std::cerr << "bench_afn_cuda: ERROR: " << e.what() << "\n";
    }
    return 1;
}
