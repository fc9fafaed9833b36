// SPDX-License-Identifier: Apache-2.0
// C ABI of the image-quality metrics: argument checks, then lib/core/metrics on the device's
// threads.
#include "afn/afn.h"

#include "api_common.h"
#include "metrics/metrics.h"

#include <string>

namespace {

using afn::throwInvalidArgument;

/// A packed view of `width x height` pixels of `stride` floats; checks the arguments.
afn::ImageView packedView(
    const float* data, const char* what, size_t width, size_t height, size_t stride)
{
    if (!data)
        throwInvalidArgument(std::string("metrics: null ") + what + " image");
    if (width == 0 || height == 0)
        throwInvalidArgument("metrics: zero-sized image");
    if (width > (1u << 16) || height > (1u << 16))
        throwInvalidArgument("metrics: image larger than 65536 pixels on a side");
    if (stride < 3 || stride > 64)
        throwInvalidArgument(
            "metrics: pixelFloatStride " + std::to_string(stride) + " out of range [3, 64]");
    afn::ImageView v;
    v.base = reinterpret_cast<const std::byte*>(data);
    v.width = static_cast<int>(width);
    v.height = static_cast<int>(height);
    v.channels = static_cast<int>(stride);
    v.pixelStride = static_cast<std::ptrdiff_t>(stride * sizeof(float));
    v.rowStride = v.pixelStride * v.width;
    return v;
}

} // namespace

extern "C" {

AFN_API bool afnComputeMetrics(AFNDevice d, const float* test, const float* reference, size_t width,
    size_t height, size_t pixelFloatStride, AFNMetrics* out)
{
    AFN_TRY
    afn::api::checkDevice(d);
    if (!out)
        throwInvalidArgument("metrics: null output");
    const afn::ImageView t = packedView(test, "test", width, height, pixelFloatStride);
    const afn::ImageView r = packedView(reference, "reference", width, height, pixelFloatStride);
    afn::metrics::FrameMetrics m;
    d->device.run([&] { m = afn::metrics::computeFrameMetrics(t, r); });
    out->psnr = m.psnr;
    out->ssim = m.ssim;
    out->rmse = m.rmse;
    out->smape = m.smape;
    out->rmseLinear = m.rmseLinear;
    out->smapeTonemapped = m.smapeTonemapped;
    out->psnr8 = m.psnr8;
    out->ssim8 = m.ssim8;
    out->rmse8 = m.rmse8;
    out->nonFiniteTest = m.nonFiniteTest;
    out->nonFiniteReference = m.nonFiniteReference;
    return true;
    AFN_CATCH(d)
    return false;
}

AFN_API bool afnComputeTemporalMetrics(AFNDevice d, const float* testPrev, const float* test,
    const float* referencePrev, const float* reference, size_t width, size_t height,
    size_t pixelFloatStride, AFNTemporalMetrics* out)
{
    AFN_TRY
    afn::api::checkDevice(d);
    if (!out)
        throwInvalidArgument("metrics: null output");
    const size_t s = pixelFloatStride;
    const afn::ImageView tp = packedView(testPrev, "previous test", width, height, s);
    const afn::ImageView t = packedView(test, "test", width, height, s);
    const afn::ImageView rp = packedView(referencePrev, "previous reference", width, height, s);
    const afn::ImageView r = packedView(reference, "reference", width, height, s);
    afn::metrics::TemporalMetrics m;
    d->device.run([&] { m = afn::metrics::computeTemporalMetrics(tp, t, rp, r); });
    out->gradientError = m.gradientError;
    out->gradientPsnr = m.gradientPsnr;
    out->nonFinite = m.nonFinite;
    return true;
    AFN_CATCH(d)
    return false;
}

} // extern "C"
