// SPDX-License-Identifier: Apache-2.0
#include "nn/baseline_input.h"

#include "base/parallel.h"
#include "methods/afn/features.h"

#include <algorithm>
#include <cmath>

namespace afn::nn {

void BaselineFeatures::compute(const Frame& in)
{
    albedo.resize(in.width, in.height, 3);
    if (in.hasAlbedo())
        std::copy(in.albedo.data(), in.albedo.data() + in.albedo.size(), albedo.data());
    else
        albedo.fill(1.0f);
    afnet::normalToUnitRange(in.normal, in.width, in.height, normal01);
    afnet::depthToUnitRange(in.depth, in.width, in.height, depth01);
}

void baselineInput(const Image& cta, const BaselineFeatures& f, Image& out)
{
    const int w = cta.width(), h = cta.height();
    out.resize(w, h, kBaselineInputChannels);
    parallelRows(h, [&](int y0, int y1) {
        for (int y = y0; y < y1; ++y)
            for (int x = 0; x < w; ++x) {
                float* o = out.at(x, y);
                const float* c = cta.at(x, y);
                for (int k = 0; k < 3; ++k)
                    o[k] = std::min(
                        std::max(std::pow(std::max(c[k], 0.0f), 1.0f / 2.2f), 0.0f), 1.0f);
                std::copy_n(f.albedo.at(x, y), 3, o + 3);
                std::copy_n(f.normal01.at(x, y), 3, o + 6);
                o[9] = f.depth01(x, y, 0);
            }
    });
}

void leakyRelu(Image& x, float slope)
{
    float* d = x.data();
    const std::size_t n = x.size();
    for (std::size_t k = 0; k < n; ++k)
        d[k] = d[k] >= 0.0f ? d[k] : slope * d[k];
}

} // namespace afn::nn
