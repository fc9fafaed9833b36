// SPDX-License-Identifier: Apache-2.0
// Fuzz target: the .afnw weights reader and the network's checks of what it reads, through the
// public API (afnSetFilterData(filter, "weights", ...) on an "afn" filter). A rejected archive must
// be an INVALID_ARGUMENT naming the problem; an accepted one must then denoise a small frame with
// every input bound into finite output.
#include "fuzz_common.h"

namespace {

constexpr const char* kTarget = "fuzz_weights";
AFNDevice g_device = nullptr;

void runFrame(AFNFilter filter)
{
    const int w = 13, h = 9;
    std::vector<std::vector<float>> planes;
    const struct {
        const char* name;
        int channels;
        AFNFormat format;
    } roles[] = { { "color", 3, AFN_FORMAT_FLOAT3 }, { "albedo", 3, AFN_FORMAT_FLOAT3 },
        { "normal", 3, AFN_FORMAT_FLOAT3 }, { "depth", 1, AFN_FORMAT_FLOAT },
        { "position", 3, AFN_FORMAT_FLOAT3 }, { "motion", 2, AFN_FORMAT_FLOAT2 } };
    for (const auto& r : roles) {
        planes.push_back(fuzz::plane(r.name, w, h, r.channels));
        afnSetFilterImage(filter, r.name, planes.back().data(), r.format, w, h, 0, 0, 0);
    }
    std::vector<float> out(static_cast<std::size_t>(w) * h * 3, -1.0f);
    afnSetFilterImage(filter, "output", out.data(), AFN_FORMAT_FLOAT3, w, h, 0, 0, 0);
    afnCommitFilter(filter);
    const char* msg = nullptr;
    AFNError e = afnGetDeviceError(g_device, &msg);
    fuzz::check(e == AFN_ERROR_NONE, kTarget,
        std::string("accepted weights fail at commit: ") + (msg ? msg : ""));
    for (int frame = 0; frame < 2; ++frame) {
        afnExecuteFilter(filter);
        e = afnGetDeviceError(g_device, &msg);
        fuzz::check(e == AFN_ERROR_NONE, kTarget,
            std::string("accepted weights fail at execute: ") + (msg ? msg : ""));
        fuzz::check(fuzz::allFinite(out), kTarget, "non-finite output from accepted weights");
    }
}

} // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***)
{
    g_device = fuzz::newSingleThreadDevice();
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
    AFNFilter filter = afnNewFilter(g_device, "afn");
    fuzz::check(filter != nullptr, kTarget, "cannot create the afn filter");
    afnSetFilterData(filter, "weights", size ? data : nullptr, size);
    const char* msg = nullptr;
    const AFNError e = afnGetDeviceError(g_device, &msg);
    const std::string text = msg ? msg : "";
    if (e == AFN_ERROR_NONE) {
        runFrame(filter);
    } else {
        fuzz::check(e == AFN_ERROR_INVALID_ARGUMENT, kTarget,
            "rejected weights give code " + std::to_string(e) + ": " + text);
        fuzz::check(text.find("weights") != std::string::npos, kTarget,
            "the rejection does not say it is about the weights: " + text);
    }
    afnReleaseFilter(filter);
    fuzz::takeError(g_device, kTarget);
    return 0;
}
