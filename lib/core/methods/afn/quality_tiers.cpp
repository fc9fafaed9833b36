// SPDX-License-Identifier: Apache-2.0
// AFN's quality tiers (see methods/afn/quality_tiers.h).
#include "methods/afn/quality_tiers.h"

#include "base/parallel.h"

#include <algorithm>
#include <chrono>

namespace afn::afnet {

namespace {

using Clock = std::chrono::steady_clock;

double msBetween(Clock::time_point a, Clock::time_point b)
{
    return std::chrono::duration<double, std::milli>(b - a).count();
}

constexpr int kPrediction = static_cast<int>(Network::Stage::Prediction);
constexpr int kFiltering = static_cast<int>(Network::Stage::Filtering);

} // namespace

void flipImage(const Image& src, bool flipX, bool flipY, Image& dst)
{
    const int w = src.width(), h = src.height(), c = src.channels();
    dst.resize(w, h, c);
    parallelRows(h, [&](int y0, int y1) {
        for (int y = y0; y < y1; ++y) {
            const int sy = flipY ? h - 1 - y : y;
            for (int x = 0; x < w; ++x) {
                const float* s = src.at(flipX ? w - 1 - x : x, sy);
                std::copy(s, s + c, dst.at(x, y));
            }
        }
    });
}

void TierRunner::run(
    QualitySettings::Tier tier, Network& net, const Inputs& in, Image& out, const Image* work)
{
    m_totals = {};
    if (tier == QualitySettings::Tier::Fast && net.variant() == Variant::Full)
        runFast(net, in, out);
    else if (tier == QualitySettings::Tier::High)
        runHigh(net, in, out);
    else {
        net.run(in, out, work);
        add(net);
    }
}

void TierRunner::add(const Network& net)
{
    for (int k = 0; k < Network::kStages; ++k) {
        const auto s = static_cast<Network::Stage>(k);
        m_totals.ms[k] += net.stageMs(s);
        m_totals.flop[k] += net.stageFlop(s);
    }
    m_totals.inputMs += net.predictionInputMs();
}

void TierRunner::runFast(Network& net, const Inputs& in, Image& out)
{
    const Clock::time_point t0 = Clock::now();
    net.prepare(in);
    m_totals.inputMs = msBetween(t0, Clock::now());
    net.predict();
    const Clock::time_point t1 = Clock::now();
    net.filterAndFuse();
    const Clock::time_point t2 = Clock::now();
    net.fusedToOutput(out);
    m_totals.ms[kPrediction] = msBetween(t0, t1);
    m_totals.ms[kFiltering] = msBetween(t1, t2);
    m_totals.flop[kPrediction] = net.stageFlop(Network::Stage::Prediction);
    m_totals.flop[kFiltering] = net.stageFlop(Network::Stage::Filtering);
}

void TierRunner::runHigh(Network& net, const Inputs& in, Image& out)
{
    const Image* given[6]
        = { in.color1, in.colorTa, in.albedo, in.normal01, in.depth01, in.history01 };
    const int w = in.color1->width(), h = in.color1->height();
    out.resize(w, h, 3);
    out.fill(0.0f);
    constexpr int kPasses = 4; // (flipX, flipY) = none, x, y, both
    for (int pass = 0; pass < kPasses; ++pass) {
        const bool fx = (pass & 1) != 0, fy = (pass & 2) != 0;
        Inputs flipped = in;
        const Image** slots[6] = { &flipped.color1, &flipped.colorTa, &flipped.albedo,
            &flipped.normal01, &flipped.depth01, &flipped.history01 };
        if (pass > 0)
            for (int k = 0; k < 6; ++k) {
                if (!given[k])
                    continue; // history01 for weights without the history input
                flipImage(*given[k], fx, fy, m_flipped[k]);
                *slots[k] = &m_flipped[k];
            }
        net.run(flipped, m_pass);
        add(net);
        // Flip back and add: pixel (x, y) of the output is (x', y') of this pass's output.
        parallelRows(h, [&](int y0, int y1) {
            for (int y = y0; y < y1; ++y) {
                const int sy = fy ? h - 1 - y : y;
                for (int x = 0; x < w; ++x) {
                    const float* s = m_pass.at(fx ? w - 1 - x : x, sy);
                    float* o = out.at(x, y);
                    for (int c = 0; c < 3; ++c)
                        o[c] += s[c];
                }
            }
        });
    }
    for (std::size_t i = 0; i < out.size(); ++i)
        out.data()[i] *= 1.0f / kPasses;
}

} // namespace afn::afnet
