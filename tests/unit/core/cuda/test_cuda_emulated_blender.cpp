// SPDX-License-Identifier: Apache-2.0
// The CUDA engine's whole default pipeline, run on the CPU through the host emulation
// (emulated_pipeline.h), against the CPU filter on real renders: the bundled Blender sequence
// (examples/sequence, 320x180, 1 spp; blender_frames.h) with the shipped model, every frame within
// the documented tolerance (afn_output_compare.h). Built in every configuration: a GPU is not
// needed.
#include "afn_output_compare.h"
#include "blender_frames.h"
#include "cuda/frame_constants.h"
#include "emulated_pipeline.h"
#include "emulated_test_util.h"
#include "filter/registry.h"
#include "methods/afn/settings.h"
#include "methods/afn/weights_source.h"
#include "raw_frames.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <iostream>

using namespace afntest;

TEST(CudaEmulated, FilterMatchesCpuOnTheBlenderSequence)
{
    const auto shipped = shippedWeights();
    if (shipped.empty())
        GTEST_SKIP() << "weights/afn.afnw is not in this checkout";
    const afn::afnet::Network net = afn::afnet::networkFromData(shipped.data(), shipped.size());
    auto cpu = afn::createFilter("afn");
    configureAsOnTheGpu(*cpu);
    cpu->params().setNumber("motion.yUp", 1.0, AFN_PARAM_BOOL);
    cpu->setData(AFN_DATA_WEIGHTS, shipped.data(), shipped.size());
    EmulatedAfnPipeline emulated(net);
    emulated.setTaa(net.trainedSpp() < afn::afnet::kTaaAutoMaxSppExclusive);
    emulated.setPostFilter(net.trainedSpp() < afn::afnet::kPostFilterAutoMaxSppExclusive);
    FrameGatherer gatherer;
    gatherer.workSkipping = true;
    gatherer.conventions.motionYUp = true;
    const Tolerance tolerance;
    for (int k = 0; k < 4; ++k) {
        const BlenderFrame b = readBlenderFrame(AFN_EXAMPLES_DIR, k);
        if (b.color.empty())
            GTEST_SKIP() << "cannot read frame " << k << " of " << AFN_EXAMPLES_DIR;
        SequenceFrame in;
        in.color = b.color;
        in.albedo = b.albedo;
        in.normal = b.normal;
        in.depth = b.depth;
        in.position = b.position;
        in.motion = b.motion;
        afn::Image cpuOut(in.color.width(), in.color.height(), 3), emuOut;
        runFrame(*cpu, in, cpuOut);
        const afn::Frame& f = gatherer.gather(in);
        emulated.run(
            f, afn::cuda::frameConstants(f, kReproject, kAccumulation, kTrust, kAux), emuOut);
        const OutputDifference d = compareOutputs(emuOut, cpuOut);
        std::cout << "[ emulated ] examples/sequence frame " << k << ": " << d.text() << "\n";
        EXPECT_TRUE(d.within(tolerance)) << "frame " << k << ": " << d.text();
    }
}

// The GPU check's raw frames (scripts/dump-gpu-frames.py, read by tests/gpu with raw_frames.h)
// hold the EXRs' passes exactly. Needs the frames written first: AFN_GPU_FRAMES=DIR after
// /usr/bin/python3 scripts/dump-gpu-frames.py examples DIR (make-gpu-bundle.sh does both).
TEST(CudaEmulated, RawFramesAreTheBlenderFrames)
{
    const char* dir = std::getenv("AFN_GPU_FRAMES");
    if (!dir)
        GTEST_SKIP() << "AFN_GPU_FRAMES is not set (scripts/dump-gpu-frames.py writes the frames)";
    for (int k = 0; k < 4; ++k) {
        char name[32];
        std::snprintf(name, sizeof name, "/frame.%04d.afnraw", k);
        SequenceFrame raw;
        ASSERT_TRUE(readRawFrame(std::string(dir) + name, raw)) << name;
        const BlenderFrame exr = readBlenderFrame(AFN_EXAMPLES_DIR, k);
        const afn::Image* a[]
            = { &raw.color, &raw.albedo, &raw.normal, &raw.depth, &raw.position, &raw.motion };
        const afn::Image* b[]
            = { &exr.color, &exr.albedo, &exr.normal, &exr.depth, &exr.position, &exr.motion };
        for (int p = 0; p < 6; ++p)
            EXPECT_TRUE(sameBits(*a[p], *b[p])) << name << " pass " << p;
    }
}
