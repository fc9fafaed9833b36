// SPDX-License-Identifier: Apache-2.0
// The learned baselines' network input (see nn/baseline_input.h).
#include "nn/baseline_input.h"

#include "base/exception.h"
#include "base/parallel.h"
#include "stages/feature_scaling.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace afn::nn {

void BaselineFeatures::compute(const Frame& in)
{
    albedo.resize(in.width, in.height, 3);
    if (in.hasAlbedo())
        std::copy(in.albedo.data(), in.albedo.data() + in.albedo.size(), albedo.data());
    else
        albedo.fill(1.0f);
    normalToUnitRange(in.normal, in.width, in.height, normal01);
    depthToUnitRange(in.depth, in.width, in.height, depth01);
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

void buildBaselineInput(
    const BaselineFeatureViews& f, int padMultiple, Image& x, Image& colorTa, const char* what)
{
    const Image* all[] = { f.colorTa, f.albedo, f.normal01, f.depth01 };
    const int chans[] = { 3, 3, 3, 1 };
    const int w = f.colorTa ? f.colorTa->width() : 0, h = f.colorTa ? f.colorTa->height() : 0;
    for (int k = 0; k < 4; ++k)
        if (!all[k] || all[k]->width() != w || all[k]->height() != h
            || all[k]->channels() != chans[k] || w <= 0 || h <= 0)
            throwInvalidArgument(std::string(what) + ": input " + std::to_string(k)
                + " missing or of the wrong shape");
    const int wp = paddedSize(w, padMultiple), hp = paddedSize(h, padMultiple);
    x.resize(wp, hp, kBaselineInputChannels);
    colorTa.resize(wp, hp, 3);
    parallelRows(hp, [&](int y0, int y1) {
        for (int y = y0; y < y1; ++y)
            for (int px = 0; px < wp; ++px) {
                const int sx = std::min(px, w - 1), sy = std::min(y, h - 1); // edge replication
                const float* c = f.colorTa->at(sx, sy);
                float* o = x.at(px, y);
                for (int k = 0; k < 3; ++k) {
                    o[k] = std::min(
                        std::max(std::pow(std::max(c[k], 0.0f), 1.0f / 2.2f), 0.0f), 1.0f);
                    o[3 + k] = f.albedo->at(sx, sy)[k];
                    o[6 + k] = f.normal01->at(sx, sy)[k];
                    colorTa(px, y, k) = c[k];
                }
                o[9] = f.depth01->at(sx, sy)[0];
            }
    });
}

void cropTo(const Image& padded, int w, int h, Image& out)
{
    out.resize(w, h, 3);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            std::copy(padded.at(x, y), padded.at(x, y) + 3, out.at(x, y));
}

} // namespace afn::nn
