// SPDX-License-Identifier: Apache-2.0
// The ONND inference graph (training/afn/baselines/onnd.py is the definition, with every choice
// the paper leaves open; same tensor names). Per frame, with L recurrent encoder levels:
//   x_0 = [T(cta), albedo, normal01, depth01]                     10 ch, padded to 16
//   a = lrelu(enc{l}a(x_l)); b = lrelu(enc{l}b([a, h_l(prev)])); h_l = lrelu(enc{l}c(b))
//   x_{l+1} = maxpool2(h_l);  y = lrelu(bott2(lrelu(bott1(x_L))))
//   y = lrelu(dec{l}b(lrelu(dec{l}a([U y, h_l]))))                  l = L-1 .. 0
//   c = max(cta, 0); net = exp(min(log1p(c) + out(y), 20)) - 1
//   irradiance = c + g * (net - c), g = contrastGate(c) (contrast_gate.h: 0 on a flat window,
//   so constant and black frames and a static scene's fixed point hold by construction)
// lrelu slope 0.1, U = nearest 2x upsampling. h_l(prev) is the previous frame's h_l, zero on the
// first frame of a history and after resetState() or a change of frame size.
#pragma once

#include "base/image.h"
#include "nn/baseline_input.h"
#include "nn/conv.h"
#include "nn/weights.h"

#include <vector>

namespace afn::onnd {

class Network {
public:
    /// Build the graph from an archive (metadata format=onnd); throws "invalid or corrupted
    /// weights" on any mismatch.
    void load(const nn::WeightsArchive& weights);
    bool loaded() const { return !m_levels.empty(); }
    int levels() const { return static_cast<int>(m_levels.size()); }

    /// Denoise one frame: `out` = demodulated irradiance (3 ch, W x H); updates the state.
    void run(const nn::BaselineFeatureViews& in, Image& out);
    /// Forget the recurrent state (the next frame starts a history).
    void resetState() { m_hasState = false; }

    /// FLOP per frame of the last run (2 x multiply-adds of every conv over the padded pixels).
    double flopPerFrame() const { return m_flop; }
    /// Parameter count (weights and biases).
    long parameters() const;

private:
    struct Level {
        nn::Conv a, b, c, decA, decB;
        Image in, aOut, cat, bOut, h, prev, pooled, up, dec;
    };
    std::vector<Level> m_levels;
    nn::Conv m_bott1, m_bott2, m_out;
    Image m_x, m_colorTa, m_bottIn, m_bottMid, m_bottOut, m_result, m_gate, m_irr;
    bool m_hasState = false;
    double m_flop = 0.0;
};

} // namespace afn::onnd
