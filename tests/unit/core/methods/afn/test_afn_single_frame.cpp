// SPDX-License-Identifier: Apache-2.0
// A temporal model on frames without a history (no motion vectors, no positions with a camera)
// runs single-frame (methods/afn/model_set.h, inputsToUse): its TA input is the frame's irradiance
// and its history input 1, exactly its input on the first frame of a shot. So such a frame's
// output is, bit for bit, that of the same frame given with motion and positions as a shot's
// first frame, and the log says which model ran and how.
#include "afn_synthetic_sequence.h"
#include "afn_test_util.h"
#include "filter/registry.h"

#include <gtest/gtest.h>

#include <cstring>
#include <string>

namespace {

using afn::Image;
using afntest::SequenceFrame;
using afntest::SequenceInputs;

constexpr int kW = 40, kH = 24;

std::unique_ptr<afn::Filter> afnFilter()
{
    auto f = afn::createFilter("afn");
    // The committed parity weights with the history input: the full input set, 1 spp.
    const auto w
        = afntest::readBytes(std::string(AFN_TEST_DATA) + "/afn_parity/weights_history.afnw");
    f->setData(AFN_DATA_WEIGHTS, w.data(), w.size());
    return f;
}

std::string modelText(const afn::Filter& f)
{
    std::string text;
    EXPECT_TRUE(f.stringStatistic(AFN_STAT_AFN_MODEL, text));
    return text;
}

} // namespace

TEST(AfnSingleFrame, AFrameWithoutHistoryIsAShotsFirstFrame)
{
    const afntest::SyntheticSequence seq(kW, kH, 5);
    SequenceInputs still;
    still.position = false;
    still.motion = false;
    for (int k : { 0, 3 }) {
        SequenceFrame noHistory = seq.frame(k, still), first = seq.frame(k, SequenceInputs {});
        auto a = afnFilter(), b = afnFilter();
        Image outA(kW, kH, 3), outB(kW, kH, 3);
        afntest::runFrame(*a, noHistory, outA);
        afntest::runFrame(*b, first, outB);
        EXPECT_EQ(std::memcmp(outA.data(), outB.data(), outA.size() * sizeof(float)), 0)
            << "frame " << k;
        EXPECT_EQ(modelText(*a),
            "model color+albedo+normal+depth+temporal, single-frame (no motion or position: the "
            "temporal branch reads this frame)");
        EXPECT_EQ(modelText(*b), "model color+albedo+normal+depth+temporal, temporal");
    }
}

TEST(AfnSingleFrame, LaterFramesWithoutHistoryReadNoAccumulation)
{
    // Frames 2 and 3 without motion through one filter: frame 3's network input is its own
    // irradiance (the accumulation, which assumes a static camera without motion, does not reach
    // the network), so with the stages that keep state across frames off (the output's TAA, the
    // post-filter's noise estimate from the history length, aux=auto's first-frame decision)
    // frame 3 gives the same bits as frame 3 alone.
    const afntest::SyntheticSequence seq(kW, kH, 5);
    SequenceInputs still;
    still.position = false;
    still.motion = false;
    auto chained = afnFilter(), fresh = afnFilter();
    chained->params().setString("taa", "off");
    fresh->params().setString("taa", "off");
    chained->params().setString("postFilter", "off");
    fresh->params().setString("postFilter", "off");
    chained->params().setString("aux", "clean"); // aux=auto decides on a run's first frame
    fresh->params().setString("aux", "clean");
    Image out2(kW, kH, 3), out3(kW, kH, 3), alone3(kW, kH, 3);
    SequenceFrame f2 = seq.frame(2, still), f3 = seq.frame(3, still), g3 = seq.frame(3, still);
    afntest::runFrame(*chained, f2, out2);
    afntest::runFrame(*chained, f3, out3);
    afntest::runFrame(*fresh, g3, alone3);
    EXPECT_EQ(std::memcmp(out3.data(), alone3.data(), out3.size() * sizeof(float)), 0);
}
