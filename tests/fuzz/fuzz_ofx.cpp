// SPDX-License-Identifier: Apache-2.0
// Fuzz target: the OpenFX plugin's parameter and clip handling, driven through the in-process test
// host of tests/plugin. The input picks the context, which clips are connected with what size,
// components, origin and frame range (mismatched clips included), pixel values (NaN, Inf, huge,
// negative, denormal), parameter values of any type (out of range and non-finite included), and
// the renders (time in or out of range, render scale, tiles, image layout).
// Properties: actions never crash, a render that succeeds fills its whole window with finite
// values, and every image the plugin fetched is released.
#include "ofx_test_host.h"

#include <fuzzer/FuzzedDataProvider.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>

using namespace ofxhost;

namespace {

constexpr const char* kTarget = "fuzz_ofx";

struct LoadedHost {
    std::unique_ptr<Host> host;
    std::unique_ptr<OfxImageEffectStruct> general, filter;
};
LoadedHost g_hosts[2];

void check(bool ok, const std::string& what)
{
    if (!ok) {
        std::fprintf(stderr, "%s: property violated: %s\n", kTarget, what.c_str());
        std::abort();
    }
}

void load(LoadedHost& h, Layout layout)
{
    h.host = std::make_unique<Host>(layout);
    std::string error;
    check(h.host->load(AFN_OFX_BINARY, &error), "cannot load the plugin: " + error);
    check(h.host->describe() == kOfxStatOK, "describe failed");
    check(h.host->describeInContext(kOfxImageEffectContextGeneral, h.general) == kOfxStatOK,
        "describe in the general context failed");
    check(h.host->describeInContext(kOfxImageEffectContextFilter, h.filter) == kOfxStatOK,
        "describe in the filter context failed");
}

float pixelValue(int mode, std::uint32_t k)
{
    k = k * 2654435761u + 12345u;
    const float u = static_cast<float>(k >> 8) / 16777216.0f;
    switch (mode) {
    case 0:
        return u;
    case 1:
        return k % 7 == 0 ? std::nanf("") : u;
    case 2:
        return k % 5 == 0 ? (k & 1 ? INFINITY : -INFINITY) : u;
    case 3:
        return (u - 0.5f) * 2e30f;
    case 4:
        return k % 11 == 0 ? 1e6f : u;
    default:
        return u * 1e-40f;
    }
}

/// A clip source of fuzzed geometry; pixel values follow `mode` (see pixelValue).
ClipSource makeSource(FuzzedDataProvider& in, const ClipSource* like)
{
    ClipSource s;
    const bool same = like && in.ConsumeIntegralInRange<int>(0, 3) != 0;
    s.width = same ? like->width : 2 * in.ConsumeIntegralInRange<int>(1, 20);
    s.height = same ? like->height : 2 * in.ConsumeIntegralInRange<int>(1, 14);
    s.originX = same ? like->originX : 2 * in.ConsumeIntegralInRange<int>(-8, 8);
    s.originY = same ? like->originY : 2 * in.ConsumeIntegralInRange<int>(-8, 8);
    s.firstFrame = same ? like->firstFrame : in.ConsumeIntegralInRange<int>(-2, 2);
    s.lastFrame = same ? like->lastFrame : s.firstFrame + in.ConsumeIntegralInRange<int>(0, 4);
    static const int kComponents[] = { 1, 3, 4 };
    s.components = kComponents[in.ConsumeIntegralInRange<int>(0, 2)];
    const int mode = in.ConsumeIntegralInRange<int>(0, 5);
    const std::uint32_t seed = in.ConsumeIntegral<std::uint32_t>();
    const ClipSource geometry = s;
    s.frame = [geometry, mode, seed](double time, double scale, std::vector<float>& pixels) {
        if (time < geometry.firstFrame || time > geometry.lastFrame)
            return false;
        const int w = static_cast<int>(geometry.width * scale);
        const int h = static_cast<int>(geometry.height * scale);
        pixels.resize(static_cast<std::size_t>(w) * h * geometry.components);
        // Mix the time's bits (a negative or huge time converted to an integer is undefined).
        std::uint64_t timeBits = 0;
        std::memcpy(&timeBits, &time, sizeof timeBits);
        const std::uint32_t t = static_cast<std::uint32_t>(timeBits ^ (timeBits >> 32)) * 977u;
        for (std::size_t i = 0; i < pixels.size(); ++i)
            pixels[i] = pixelValue(mode, seed ^ t ^ static_cast<std::uint32_t>(i * 31));
        return true;
    };
    return s;
}

void setParam(FuzzedDataProvider& in, Host& host, OfxImageEffectStruct* inst)
{
    const auto& params = inst->params.params;
    if (params.empty())
        return;
    const OfxParamStruct& p = *params[in.ConsumeIntegralInRange<std::size_t>(0, params.size() - 1)];
    if (p.type == kOfxParamTypeGroup)
        return;
    if (p.type == kOfxParamTypeString) {
        static const char* const kStrings[]
            = { "", AFN_TEST_WEIGHTS, "/nonexistent/weights.afnw", AFN_OFX_BINARY, "/" };
        const int pick = in.ConsumeIntegralInRange<int>(0, 5);
        host.setParam(inst, p.name,
            pick < 5 ? std::string(kStrings[pick]) : in.ConsumeRandomLengthString(32));
        return;
    }
    double v;
    switch (in.ConsumeIntegralInRange<int>(0, 3)) {
    case 0: {
        const std::uint64_t bits = in.ConsumeIntegral<std::uint64_t>();
        std::memcpy(&v, &bits, sizeof v); // any double, NaN and Inf included
        break;
    }
    case 1:
        v = in.ConsumeIntegralInRange<int>(-3, 12);
        break;
    default:
        v = in.ConsumeFloatingPointInRange<double>(-2.0, 1100.0);
    }
    if (p.type != kOfxParamTypeDouble && !(std::fabs(v) < 1e9))
        v = 0.0; // the host converts to int: keep that conversion defined
    host.setParam(inst, p.name, v);
}

void render(FuzzedDataProvider& in, Host& host, OfxImageEffectStruct* inst, const ClipSource& src)
{
    const double time = in.ConsumeBool()
        ? in.ConsumeIntegralInRange<int>(
            static_cast<int>(src.firstFrame), static_cast<int>(src.lastFrame))
        : in.ConsumeIntegralInRange<int>(-6, 8) + (in.ConsumeBool() ? 0.5 : 0.0);
    const double scale = in.ConsumeBool() ? 1.0 : 0.5;
    // Tiles of at least two pixels a side, as a host cuts them.
    const int maxTiles
        = std::max(1, std::min(3, std::min(src.width, src.height) * scale > 8 ? 3 : 1));
    const int tiles = in.ConsumeIntegralInRange<int>(1, maxTiles);
    Frame out;
    const OfxStatus s = host.renderFrame(inst, time, scale, tiles, out);
    if (s != kOfxStatOK)
        return;
    for (std::size_t i = 0; i < out.rgba.size(); ++i)
        check(std::isfinite(out.rgba[i]),
            "render succeeded but output value " + std::to_string(i) + " is not finite");
}

} // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***)
{
    load(g_hosts[0], Layout {});
    Layout flipped;
    flipped.negativeRowBytes = true;
    flipped.rowPaddingPixels = 3;
    load(g_hosts[1], flipped);
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
    FuzzedDataProvider in(data, size);
    LoadedHost& h = g_hosts[in.ConsumeBool() ? 1 : 0];
    const bool general = in.ConsumeBool();
    std::map<std::string, ClipSource> sources;
    sources["Source"] = makeSource(in, nullptr);
    if (general)
        for (const char* clip : { "Albedo", "Normal", "Depth", "Position", "Motion" })
            if (in.ConsumeBool())
                sources[clip] = makeSource(in, &sources["Source"]);
    std::map<std::string, const ClipSource*> inputs;
    for (const auto& [name, src] : sources)
        inputs[name] = &src;
    OfxStatus status = kOfxStatFailed;
    auto inst = h.host->createInstance(general ? *h.general : *h.filter,
        general ? kOfxImageEffectContextGeneral : kOfxImageEffectContextFilter, inputs, &status);
    if (status == kOfxStatOK) {
        for (int i = 0, n = in.ConsumeIntegralInRange<int>(0, 6); i < n; ++i)
            setParam(in, *h.host, inst.get());
        for (int i = 0, n = in.ConsumeIntegralInRange<int>(1, 3); i < n; ++i)
            render(in, *h.host, inst.get(), sources["Source"]);
        h.host->destroyInstance(inst.get());
    }
    check(h.host->liveImages() == 0, "the plugin did not release every image it fetched");
    return 0;
}
