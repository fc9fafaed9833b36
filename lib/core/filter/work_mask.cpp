// SPDX-License-Identifier: Apache-2.0
#include "filter/work_mask.h"

#include "base/parallel.h"
#include "filter/filter.h"

#include <atomic>
#include <cmath>
#include <limits>

namespace afn {

const ParamBinding<WorkSettings>& workBinding()
{
    using S = WorkSettings;
    static const ParamBinding<S> binding
        = ParamBinding<S>()
              .add(&S::skip, "skip", "Skip unneeded pixels",
                  "pixels that need no denoising (background: depth non-finite or beyond "
                  "denoisingRange; alpha 0; outside the mask image) may take the method's cheap "
                  "path")
              .add(&S::denoisingRange, "denoisingRange", 0.0, 3.4e38, "Denoising range",
                  "depth (scene units) at or beyond which a pixel is background and skipped "
                  "(NRD denoisingRange; Blender Cycles writes 1e10 for the background)");
    return binding;
}

std::vector<ParamDesc> workDescriptors(const std::string& skipHelp)
{
    std::vector<ParamDesc> table = workBinding().descriptors();
    for (ParamDesc& d : table)
        if (d.name == "skip")
            d.help += ". In this method: "
                + (skipHelp.empty() ? std::string("not implemented (every pixel is denoised; the "
                                                  "skipped share is only reported)")
                                    : skipHelp);
    return table;
}

namespace {

const ImageBinding* find(const std::map<std::string, ImageBinding>& m, const char* name)
{
    auto it = m.find(name);
    return it == m.end() ? nullptr : &it->second;
}

/// True when the geometry at (x, y) is background (see work_mask.h).
bool background(const ImageView* depth, const ImageView* position, float range, int x, int y)
{
    if (depth) {
        const float z = depth->at(x, y)[0];
        return !std::isfinite(z) || z >= range;
    }
    if (position) {
        const float* p = position->at(x, y);
        double len2 = 0.0;
        for (int c = 0; c < 3; ++c) {
            if (!std::isfinite(p[c]))
                return true;
            len2 += static_cast<double>(p[c]) * p[c];
        }
        return len2 >= static_cast<double>(range) * range;
    }
    return false;
}

} // namespace

double buildWorkMask(
    const std::map<std::string, ImageBinding>& images, const WorkSettings& s, Frame& f)
{
    const ImageBinding* depthB = find(images, AFN_IMAGE_DEPTH);
    const ImageBinding* positionB = find(images, AFN_IMAGE_POSITION);
    const ImageBinding* maskB = find(images, AFN_IMAGE_MASK);
    const bool alpha = !f.alpha.empty();
    if (!s.skip || (!depthB && !positionB && !maskB && !alpha)) {
        f.work = Image();
        return 0.0;
    }
    const ImageView depthV = depthB ? depthB->view() : ImageView {};
    const ImageView positionV = positionB ? positionB->view() : ImageView {};
    const ImageView maskV = maskB ? maskB->view() : ImageView {};
    const ImageView* depth = depthB ? &depthV : nullptr;
    const ImageView* position = positionB && !depthB ? &positionV : nullptr;

    auto needed = [&](int x, int y) {
        bool n = !background(depth, position, s.denoisingRange, x, y);
        if (n && alpha)
            n = f.alpha(x, y, 0) != 0.0f;
        if (n && maskB)
            n = maskV.at(x, y)[0] > 0.0f; // NaN compares false: not needed
        return n;
    };
    // A read-only pass first, stopping at the first pixel that needs no work: a frame where every
    // pixel needs work (the usual case with a depth input and no sky) then writes and allocates
    // nothing (a mask allocated and freed per frame cost page faults on every frame).
    // With only a packed depth to test, a row is read as one branch-free (vectorised) run:
    // needed(x, y) is then z < range and z > -inf (NaN fails both; +inf is >= any range).
    const bool depthOnly = depth && !alpha && !maskB
        && depthV.pixelStride == static_cast<std::ptrdiff_t>(sizeof(float));
    auto rowNeedsAll = [&](int y) {
        if (depthOnly) {
            const float* z = depthV.at(0, y);
            const float range = s.denoisingRange, below = -std::numeric_limits<float>::infinity();
            int all = 1;
            for (int x = 0; x < f.width; ++x)
                all &= static_cast<int>(z[x] < range) & static_cast<int>(z[x] > below);
            return all != 0;
        }
        for (int x = 0; x < f.width; ++x)
            if (!needed(x, y))
                return false;
        return true;
    };
    std::atomic<bool> anySkipped { false };
    parallelRows(f.height, [&](int y0, int y1) {
        for (int y = y0; y < y1 && !anySkipped.load(std::memory_order_relaxed); ++y)
            if (!rowNeedsAll(y)) {
                anySkipped = true;
                return;
            }
    });
    if (!anySkipped) {
        f.work = Image(); // every pixel needs work: methods run their unrestricted path
        return 0.0;
    }
    Image& work = f.work; // kept across frames while frames have skipped pixels
    work.resize(f.width, f.height, 1);
    std::atomic<std::int64_t> skipped { 0 };
    parallelRows(f.height, [&](int y0, int y1) {
        std::int64_t n = 0;
        for (int y = y0; y < y1; ++y)
            for (int x = 0; x < f.width; ++x) {
                const bool need = needed(x, y);
                work(x, y, 0) = need ? 1.0f : 0.0f;
                n += need ? 0 : 1;
            }
        skipped += n;
    });
    return static_cast<double>(skipped) / (static_cast<double>(f.width) * f.height);
}

} // namespace afn
