// SPDX-License-Identifier: Apache-2.0
// AFN refinement o = i + ref3(relu(ref2(relu(ref1([T(i), albedo, normal01, depth01]))))) in row
// strips (see methods/afn/network.h).
//
// Memory: the refinement's input (10 ch) and hidden layers (16 + 16 ch) and ref3's output are
// 45 floats per pixel, 180 B/px = 5.6 GiB at 8K, if stored at frame size. Each strip of kStrip
// output rows instead computes its input rows with a 3-row halo, ref1 with 2, ref2 with 1, into
// thread-local buffers of (kStrip + 6) rows, and writes only o. The halo rows are computed again
// by the neighbouring strip (4 % more ref1/ref2 work at kStrip = 64; not counted in the GFLOP).
// Every pixel is computed by the same operations in the same order whatever the strip or thread,
// so the result is identical to a whole-frame pass and bit-identical across thread counts. Strip
// buffers use strip-local row numbers; rows outside [0, strip height) read as zero, which is
// the zero padding at the true image border and is never reached at an inner strip edge.
// refineRows() takes the images it reads as arguments: the whole-frame path passes the frame,
// the stripe path (network_stripes.cpp) its stripe window, whose edges are image borders only
// where the window reaches the frame's (it holds 3 more rows than refined on both sides).
#include "methods/afn/network.h"

#include "base/parallel.h"

#include <algorithm>

namespace afn::afnet {

namespace {

constexpr int kStrip = 64; // output rows per strip
constexpr int kRefineChannels = 10; // T(i) 3, albedo 3, normal01 3, depth01 1

struct StripBuffers {
    Image in, r1, r2;
    std::vector<float> r3;
    std::vector<float> tone; ///< one row of the tone-mapped fused image
};

} // namespace

void Network::refineRows(
    const Image& fused, const Image& x, int y0, int y1, float* dst, long dstRow) const
{
    thread_local StripBuffers b;
    const int wp = fused.width(), hp = fused.height();
    const int a0 = std::max(0, y0 - 3), a1 = std::min(hp, y1 + 3); // strip rows
    const int rows = a1 - a0;
    b.in.resize(wp, rows, kRefineChannels);
    b.r1.resize(wp, rows, m_ref1.outChannels());
    b.r2.resize(wp, rows, m_ref2.outChannels());
    b.tone.resize(static_cast<std::size_t>(3) * wp);
    for (int y = a0; y < a1; ++y) {
        toneMapNetworkInput(fused.at(0, y), b.tone.data(), 3 * wp);
        for (int xx = 0; xx < wp; ++xx) {
            const float* t = b.tone.data() + 3 * xx;
            const float* f = x.at(xx, y);
            float* o = b.in.at(xx, y - a0);
            for (int c = 0; c < 3; ++c)
                o[c] = t[c];
            for (int c = 0; c < 7; ++c)
                o[3 + c] = f[6 + c]; // albedo, normal01, depth01
        }
    }
    // Local output rows of each layer: ref1 [y0 - 2, y1 + 2), ref2 [y0 - 1, y1 + 1).
    auto local = [&](int y) { return std::clamp(y, a0, a1) - a0; };
    const int n1 = m_ref1.outChannels(), n2 = m_ref2.outChannels();
    m_ref1.runRows(nullptr, b.in, local(y0 - 2), local(y1 + 2), b.r1.at(0, local(y0 - 2)),
        static_cast<long>(wp) * n1, n1, true);
    m_ref2.runRows(nullptr, b.r1, local(y0 - 1), local(y1 + 1), b.r2.at(0, local(y0 - 1)),
        static_cast<long>(wp) * n2, n2, true);
    b.r3.resize(static_cast<std::size_t>(wp) * (y1 - y0) * 3);
    m_ref3.runRows(
        nullptr, b.r2, y0 - a0, y1 - a0, b.r3.data(), static_cast<long>(wp) * 3, 3, false);
    for (int y = y0; y < y1; ++y) {
        const float* i = fused.at(0, y);
        const float* r = b.r3.data() + static_cast<std::size_t>(y - y0) * wp * 3;
        float* o = dst + (y - y0) * dstRow;
        for (int k = 0; k < 3 * wp; ++k)
            o[k] = i[k] + r[k];
    }
}

void Network::refine()
{
    const int wp = m_fused.width(), hp = m_fused.height();
    m_out.resize(wp, hp, 3);
    if (m_variant != Variant::Full)
        std::copy(m_fused.data(), m_fused.data() + m_fused.size(), m_out.data());
    parallelRows(
        hp,
        [&](int y0, int y1) {
            if (m_variant == Variant::Full)
                refineRows(m_fused, m_x, y0, y1, m_out.at(0, y0), static_cast<long>(wp) * 3);
            if (m_albedoTrust) // back to the albedo-demodulated space (albedo_trust.h)
                undoAlbedoTrustRows(
                    m_x, m_trust, y0, y1, wp, m_out.at(0, y0), static_cast<long>(wp) * 3);
        },
        kStrip);
}

} // namespace afn::afnet
