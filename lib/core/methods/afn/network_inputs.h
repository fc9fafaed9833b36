// SPDX-License-Identifier: Apache-2.0
// NetworkInputs assembles the five network inputs of a frame for a model of a given input set
// (input_set.h): the roles the model was not trained for are held at their neutral values
// (albedo 1, i.e. the colour itself is filtered and nothing is remodulated; normal01 0.5;
// depth01 0), and without the temporal branch the TA input is the current irradiance (and
// history01, the reciprocal of the frames the TA input holds, is 1 everywhere). The
// feature scaling itself (normal01, depth01) is stages/feature_scaling.h, shared with the
// learned baselines.
#pragma once

#include "base/image.h"
#include "methods/afn/input_set.h"
#include "methods/afn/network.h"
#include "stages/demodulate.h"
#include "stages/feature_scaling.h"

namespace afn {
struct Frame;
}

namespace afn::afnet {

class NetworkInputs {
public:
    /// Assemble the inputs of `in` for a model of input set `use` (covered by the frame's), from
    /// the shared stages' irradiance and temporal accumulation (these and `in` must outlive the
    /// inputs). history01 is made from `historyLength` (1 ch, frames accumulated) when it is
    /// given, and left empty (no memory) when null: only models with the history input and the
    /// feature output read it.
    void prepare(const Frame& in, const InputSet& use, const Image& irradiance,
        const Image& accumulated, const Image* historyLength);
    Inputs inputs() const
    {
        return { m_color1, m_colorTa, m_albedo, &m_normal01, &m_depth01, &m_history01 };
    }
    const Image& color1() const { return *m_color1; }
    const Image& colorTa() const { return *m_colorTa; }
    const Image& albedo() const { return *m_albedo; }
    const Image& normal01() const { return m_normal01; }
    const Image& depth01() const { return m_depth01; }
    /// 1 / the history length at each pixel, clamped to [1/255, 1]; 1 without the temporal
    /// branch or where the length is not finite. Empty when prepare() had no history length.
    const Image& history01() const { return m_history01; }
    /// The radiance of the network output `result`: remodulated by the albedo when the model
    /// uses it, else clamped to [0, kMaxIrradiance] as the remodulation does. `out` may be
    /// `result` (in place).
    void radiance(const Frame& in, const Image& result, Image& out) const;
    /// What radiance() multiplies channel k of pixel (x, y) of the result by.
    float radianceFactor(const Frame& in, int x, int y, int k) const
    {
        return m_use.albedo ? albedoFactorAt(in, x, y, k) : 1.0f;
    }

private:
    void makeHistory01(const Image& length, bool temporal, int w, int h);

    InputSet m_use;
    const Image* m_color1 = nullptr;
    const Image* m_colorTa = nullptr;
    /// The frame's albedo itself when the model uses it (no copy: saves a frame-size image), else
    /// m_ones.
    const Image* m_albedo = nullptr;
    Image m_colour, m_colourTa, m_ones, m_normal01, m_depth01, m_history01;
};

} // namespace afn::afnet
