// SPDX-License-Identifier: Apache-2.0
#include "param_display.h"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace afnofx {

namespace {

struct Label {
    const char* id;
    const char* label;
};

// Methods the plugin knows by name; a method added to the library later shows as its id in
// capitals followed by the library's one-line description (see methodLabel).
const Label kMethodLabels[] = {
    { "identity", "Identity (no denoising: the source, sanitised)" },
    { "ta", "TA (temporal accumulation)" },
    { "svgf", "SVGF (spatiotemporal variance-guided filtering)" },
    { "bmfr", "BMFR (blockwise multi-order feature regression)" },
    { "afn", "AFN (adaptive fusion network)" },
    { "onnd", "ONND (recurrent denoising autoencoder)" },
    { "mrkp", "MRKP (MR-KP: multi-resolution kernel prediction)" },
};

const Label kDeviceLabels[] = {
    { "cpu", "CPU" },
    { "cuda", "CUDA (NVIDIA GPU)" },
    { "auto", "Auto (CUDA when it can run the method, else CPU)" },
};

template <size_t N> const char* find(const Label (&table)[N], const std::string& id)
{
    for (const Label& l : table)
        if (id == l.id)
            return l.label;
    return nullptr;
}

std::string upper(std::string s)
{
    std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::toupper(c); });
    return s;
}

// Library parameters (by name) that act only through auxiliary inputs: history acceptance tests
// on position, normal and depth, the aux prefilter, SVGF's normal and depth edge-stopping (the
// guides are empty without those inputs, lib/core/methods/svgf/guide.cpp).
const char* const kAuxOnlyParams[] = { "positionLimit", "positionLimitSquared",
    "normalLimitSquared", "depthLimit", "aux", "sigmaN", "sigmaZ" };

} // namespace

std::string methodLabel(const std::string& id)
{
    if (const char* l = find(kMethodLabels, id))
        return l;
    const char* d = afnGetFilterTypeDescription(id.c_str());
    return d && *d ? upper(id) + " (" + d + ")" : id;
}

std::string deviceLabel(const std::string& id)
{
    const char* l = find(kDeviceLabels, id);
    return l ? l : id;
}

// Choice: a slider spanning a thousand times the default hides the useful part in its first
// pixels. When the accepted range reaches beyond 10x the default, the slider shows [min, 4x the
// default] (sigmaL: default 4, accepted 0..1000, shown 0..16); a zero default shows up to 1
// (floats) or 64 (integers). Narrow ranges (alpha 0..1, iterations 0..10) are shown whole.
DisplayRange displayRange(const AFNParamInfo& info)
{
    DisplayRange r { info.minValue, info.maxValue };
    const double d = info.defaultValue;
    const double wide = d > 0.0 ? 10.0 * d : info.type == AFN_PARAM_INT ? 64.0 : 1.0;
    if (info.maxValue > wide && d >= 0.0)
        r.max = d > 0.0 ? 4.0 * d : wide;
    if (info.minValue < -wide && d == 0.0)
        r.min = -r.max; // symmetric ranges around a zero default
    r.min = std::max(r.min, info.minValue);
    r.max = std::min(std::max(r.max, r.min), info.maxValue);
    return r;
}

bool needsAuxInputs(const char* name, bool sharedByAllMethods)
{
    if (sharedByAllMethods)
        return true; // input conventions: normal space, depth kind, motion, demodulated colour
    for (const char* n : kAuxOnlyParams)
        if (std::strcmp(n, name) == 0)
            return true;
    return false;
}

} // namespace afnofx
