// SPDX-License-Identifier: Apache-2.0
// Rebuilding the beauty from light-path passes (PassRecipe) and measuring how far it is from the
// beauty the renderer wrote, on the tone map of afn's metrics (docs/metrics.md).
#include "afn/io.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

namespace afn::io {
namespace {

double tonemap(double x)
{
    return std::clamp(std::pow(std::max(x, 0.0), 1.0 / 2.2), 0.0, 1.0);
}

} // namespace

RoleImage recompose(
    const PassRecipe& recipe, const std::map<std::string, RoleImage>& passes, int width, int height)
{
    RoleImage sum;
    sum.width = width;
    sum.height = height;
    sum.components = 3;
    const std::size_t n = static_cast<std::size_t>(width) * height;
    sum.pixels.assign(n * 3, 0.0f);
    auto image = [&](const std::string& name) -> const RoleImage* {
        auto it = passes.find(name);
        return it != passes.end() && it->second.width == width && it->second.height == height
                && it->second.components >= 3
            ? &it->second
            : nullptr;
    };
    for (const LightPass& light : recipe.lights) {
        const RoleImage* p = image(light.name);
        if (!p)
            continue;
        const RoleImage* f = light.factor.empty() ? nullptr : image(light.factor);
        if (!light.factor.empty() && !f)
            continue;
        for (std::size_t i = 0; i < n; ++i)
            for (int c = 0; c < 3; ++c) {
                const float v = p->pixels[i * p->components + c];
                sum.pixels[i * 3 + c] += f ? v * f->pixels[i * f->components + c] : v;
            }
    }
    return sum;
}

Recomposition recompositionError(const RoleImage& recomposed, const RoleImage& beauty)
{
    Recomposition r;
    const std::size_t n = static_cast<std::size_t>(beauty.width) * beauty.height;
    if (recomposed.width != beauty.width || recomposed.height != beauty.height || n == 0
        || recomposed.components < 3 || beauty.components < 3) {
        r.psnr = -std::numeric_limits<double>::infinity();
        return r;
    }
    double se = 0.0, sumBeauty = 0.0, seLinear = 0.0, sumAbs = 0.0;
    for (std::size_t i = 0; i < n; ++i)
        for (int c = 0; c < 3; ++c) {
            const double a = recomposed.pixels[i * recomposed.components + c];
            const double b = beauty.pixels[i * beauty.components + c];
            const double d = tonemap(a) - tonemap(b);
            se += d * d;
            r.maxAbsolute = std::max(r.maxAbsolute, std::abs(a - b));
            sumBeauty += b;
            seLinear += (a - b) * (a - b);
            sumAbs += std::abs(b);
        }
    const double mse = se / (3.0 * n);
    r.psnr = mse > 0.0 ? 10.0 * std::log10(1.0 / mse) : std::numeric_limits<double>::infinity();
    r.meanBeauty = sumBeauty / (3.0 * n);
    const double meanAbs = sumAbs / (3.0 * n);
    const double rms = std::sqrt(seLinear / (3.0 * n));
    r.relativeRms = meanAbs > 0.0 ? rms / meanAbs : (rms > 0.0 ? 1.0 : 0.0);
    return r;
}

std::optional<Recomposition> recompositionOf(const FrameImages& frame)
{
    auto color = frame.roles.find(Role::Color);
    if (frame.passRecipe.empty() || color == frame.roles.end() || frame.passes.empty())
        return std::nullopt;
    const RoleImage sum
        = recompose(frame.passRecipe, frame.passes, color->second.width, color->second.height);
    return recompositionError(sum, color->second);
}

std::string recompositionWarning(const PassRecipe& recipe, const Recomposition& error)
{
    std::string text;
    if (error.psnr < kRecompositionWarnPsnr || error.relativeRms > kRecompositionWarnRelative) {
        char buf[200];
        std::snprintf(buf, sizeof buf,
            "the light passes do not add up to the beauty: PSNR %.1f dB (tone-mapped), relative "
            "RMS error %.3g, largest difference %.4g (mean beauty %.4g)",
            error.psnr, error.relativeRms, error.maxAbsolute, error.meanBeauty);
        text = buf;
        text += "; formula " + recipe.formula;
    }
    if (!recipe.missing.empty()) {
        std::string names;
        for (const std::string& m : recipe.missing)
            names += (names.empty() ? "" : ", ") + m;
        text += (text.empty() ? "" : "; ") + std::string("passes missing from the formula: ")
            + names;
    }
    return text;
}

} // namespace afn::io
