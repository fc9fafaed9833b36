// SPDX-License-Identifier: Apache-2.0
// AFN network inputs per input set (see methods/afn/network_inputs.h).
#include "methods/afn/network_inputs.h"

#include "base/parallel.h"
#include "filter/frame.h"
#include "stages/demodulate.h"
#include "stages/temporal_accumulation.h"

#include <algorithm>

namespace afn::afnet {

namespace {

/// The radiance of a demodulated image (irradiance x the frame's albedo factor), <= kMaxIrradiance.
void undemodulate(const Frame& in, const Image& irradiance, Image& out)
{
    remodulate(in, irradiance, out);
    for (std::size_t k = 0; k < out.size(); ++k)
        out.data()[k] = std::min(out.data()[k], kMaxIrradiance);
}

} // namespace

void NetworkInputs::prepare(const Frame& in, const InputSet& use, const Image& irradiance,
    const Image& accumulated, const Image* historyLength)
{
    m_use = use;
    m_color1 = &irradiance;
    m_colorTa = use.temporal ? &accumulated : &irradiance;
    if (use.albedo) {
        m_albedo = &in.albedo; // the frame outlives the inputs (prepare's contract)
        m_ones = Image();
    } else {
        m_ones.resize(in.width, in.height, 3);
        m_ones.fill(1.0f);
        m_albedo = &m_ones;
        if (in.hasAlbedo()) {
            // A model without albedo filters the colour itself (training/afn/input_sets.py mask).
            undemodulate(in, irradiance, m_colour);
            m_color1 = &m_colour;
            m_colorTa = &m_colour;
            if (use.temporal) {
                undemodulate(in, accumulated, m_colourTa);
                m_colorTa = &m_colourTa;
            }
        }
    }
    if (!historyLength) {
        m_history01 = Image();
    } else {
        makeHistory01(*historyLength, use.temporal, in.width, in.height);
    }
    static const Image none;
    normalToUnitRange(use.normal ? in.normal : none, in.width, in.height, m_normal01);
    depthToUnitRange(use.depth ? in.depth : none, in.width, in.height, m_depth01);
}

void NetworkInputs::makeHistory01(const Image& length, bool temporal, int w, int h)
{
    m_history01.resize(w, h, 1);
    const bool lengths
        = temporal && length.width() == w && length.height() == h && length.channels() == 1;
    parallelRows(h, [&](int y0, int y1) {
        float* o = m_history01.at(0, y0);
        const float* len = lengths ? length.at(0, y0) : nullptr;
        for (std::size_t k = 0, n = static_cast<std::size_t>(y1 - y0) * w; k < n; ++k) {
            const float s = len ? len[k] : 1.0f;
            // s >= 1 normally; a NaN or a length below 1 counts as no history.
            o[k] = s > 1.0f ? std::max(1.0f / s, 1.0f / kMaxHistoryLength) : 1.0f;
        }
    });
}

void NetworkInputs::radiance(const Frame& in, const Image& result, Image& out) const
{
    if (m_use.albedo) {
        remodulate(in, result, out);
        return;
    }
    out.resize(in.width, in.height, 3);
    for (std::size_t k = 0; k < out.size(); ++k) {
        const float v = result.data()[k];
        out.data()[k] = v > 0.0f ? std::min(v, kMaxIrradiance) : 0.0f;
    }
}

} // namespace afn::afnet
