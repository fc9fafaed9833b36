// SPDX-License-Identifier: Apache-2.0
// C ABI of the auxiliary-buffer noise estimate: argument checks, then lib/core/stages/aux_noise on
// the device's threads.
#include "afn/afn.h"

#include "api_common.h"
#include "stages/aux_noise.h"

#include <string>

extern "C" {

AFN_API bool afnEstimateAuxNoise(AFNDevice d, const char* role, const float* data, size_t width,
    size_t height, size_t pixelFloatStride, AFNAuxNoise* out)
{
    AFN_TRY
    afn::api::checkDevice(d);
    if (!out || !data || !role)
        afn::throwInvalidArgument("aux noise: null argument");
    const std::string r = role;
    afn::AuxKind kind;
    size_t channels = 3;
    if (r == AFN_IMAGE_ALBEDO) {
        kind = afn::AuxKind::Albedo;
    } else if (r == AFN_IMAGE_NORMAL) {
        kind = afn::AuxKind::Normal;
    } else if (r == AFN_IMAGE_DEPTH) {
        kind = afn::AuxKind::Depth;
        channels = 1;
    } else {
        afn::throwInvalidArgument("aux noise: unknown role '" + r + "' (albedo, normal, depth)");
    }
    if (width == 0 || height == 0 || width > (1u << 16) || height > (1u << 16))
        afn::throwInvalidArgument("aux noise: image size out of range");
    if (pixelFloatStride < channels || pixelFloatStride > 64)
        afn::throwInvalidArgument("aux noise: pixelFloatStride " + std::to_string(pixelFloatStride)
            + " out of range [" + std::to_string(channels) + ", 64]");
    afn::ImageView v;
    v.base = reinterpret_cast<const std::byte*>(data);
    v.width = static_cast<int>(width);
    v.height = static_cast<int>(height);
    v.channels = static_cast<int>(channels);
    v.pixelStride = static_cast<std::ptrdiff_t>(pixelFloatStride * sizeof(float));
    v.rowStride = v.pixelStride * v.width;
    double share = 0.0;
    d->device.run([&] { share = afn::speckleShare(v, kind); });
    out->speckle = share;
    out->noisy = share > afn::kAuxNoisyShare;
    return true;
    AFN_CATCH(d)
    return false;
}

} // extern "C"
