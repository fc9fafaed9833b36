// SPDX-License-Identifier: Apache-2.0
// Helpers shared by the fuzz targets: property checks that abort (libFuzzer then saves the input),
// the targets' device, the device error rule of the C API, and a small deterministic input frame.
#pragma once

#include <afn/afn.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

namespace fuzz {

/// Abort with a message when a property does not hold.
inline void check(bool ok, const char* target, const std::string& what)
{
    if (!ok) {
        std::fprintf(stderr, "%s: property violated: %s\n", target, what.c_str());
        std::abort();
    }
}

/// A committed default device running one thread (the targets' device, made once at start).
inline AFNDevice newSingleThreadDevice()
{
    AFNDevice device = afnNewDevice(AFN_DEVICE_TYPE_DEFAULT);
    afnSetDeviceInt(device, "numThreads", 1);
    afnCommitDevice(device);
    return device;
}

/// Take the device's pending error and check it is one a caller can act on: bad input is
/// INVALID_ARGUMENT / INVALID_OPERATION / UNSUPPORTED with a message, never UNKNOWN (an unexpected
/// exception inside the library) or OUT_OF_MEMORY (inputs here are small).
inline AFNError takeError(AFNDevice device, const char* target)
{
    const char* msg = nullptr;
    const AFNError e = afnGetDeviceError(device, &msg);
    const std::string text = msg ? msg : "";
    check(e == AFN_ERROR_NONE || e == AFN_ERROR_INVALID_ARGUMENT || e == AFN_ERROR_INVALID_OPERATION
            || e == AFN_ERROR_UNSUPPORTED,
        target, "unexpected error code " + std::to_string(e) + ": " + text);
    check(e == AFN_ERROR_NONE || !text.empty(), target, "an error without a message");
    return e;
}

/// A plausible packed plane of `channels` floats per pixel for an input role.
inline std::vector<float> plane(const std::string& role, int w, int h, int channels)
{
    std::vector<float> v(static_cast<std::size_t>(w) * h * channels);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int c = 0; c < channels; ++c) {
                float& o = v[(static_cast<std::size_t>(y) * w + x) * channels + c];
                const float s = static_cast<float>((x * 7 + y * 13 + c * 5) % 17) / 17.0f;
                if (role == "normal")
                    o = c == 2 ? 1.0f : 0.0f;
                else if (role == "depth")
                    o = 2.0f + 0.01f * static_cast<float>(x + y);
                else if (role == "position")
                    o = c == 0 ? static_cast<float>(x) : c == 1 ? static_cast<float>(y) : 5.0f;
                else if (role == "motion")
                    o = c == 0 ? 0.5f : -0.25f;
                else
                    o = 0.1f + s;
            }
    return v;
}

/// True when every value is finite.
inline bool allFinite(const std::vector<float>& v)
{
    for (float x : v)
        if (!std::isfinite(x))
            return false;
    return true;
}

} // namespace fuzz
