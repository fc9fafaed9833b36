// SPDX-License-Identifier: Apache-2.0
// Fuzz target: the C API's setters, getters and the set -> commit -> execute cycle. The input is a
// script of calls on one filter of any method: parameters by name (known and made up) with any
// value (NaN, Inf, denormals, out of range), arrays, data blobs, images of any format, size and
// stride (negative row strides included) with any values, unbinding, commits, executes, resets.
// Every image buffer is allocated to exactly the bytes its description covers, so AddressSanitizer
// reports any access outside it. Properties: errors are ones a caller can act on (fuzz_common.h),
// and every successful execute writes finite values into the whole output.
#include "fuzz_common.h"

#include <fuzzer/FuzzedDataProvider.h>

#include <map>
#include <memory>

namespace {

constexpr const char* kTarget = "fuzz_api_params";
AFNDevice g_device = nullptr;

const char* const kImageNames[]
    = { "color", "albedo", "normal", "depth", "position", "motion", "alpha", "output", "bogus" };

/// An image buffer exactly as large as its description needs.
struct Bound {
    std::vector<unsigned char> bytes;
    void* ptr = nullptr; ///< pointer handed to the API (row 0)
    int width = 0, height = 0, channels = 0;
    std::size_t pixelStride = 0;
    std::ptrdiff_t rowStride = 0;
    /// Value c of pixel (x, y), read bytewise (the buffer may be unaligned).
    float value(int x, int y, int c) const
    {
        float v;
        std::memcpy(&v,
            static_cast<const unsigned char*>(ptr) + static_cast<std::ptrdiff_t>(y) * rowStride
                + static_cast<std::ptrdiff_t>(x) * static_cast<std::ptrdiff_t>(pixelStride) + 4 * c,
            sizeof v);
        return v;
    }
};

float anyFloat(FuzzedDataProvider& in)
{
    switch (in.ConsumeIntegralInRange<int>(0, 3)) {
    case 0: { // any bit pattern: NaN, Inf, denormals
        const std::uint32_t bits = in.ConsumeIntegral<std::uint32_t>();
        float f;
        std::memcpy(&f, &bits, sizeof f);
        return f;
    }
    case 1:
        return static_cast<float>(in.ConsumeIntegralInRange<int>(-3, 1100));
    default:
        return in.ConsumeFloatingPointInRange<float>(-2.0f, 2.0f);
    }
}

std::string paramName(FuzzedDataProvider& in, const std::string& method)
{
    const int n = afnGetFilterTypeNumParams(method.c_str());
    const int pick = in.ConsumeIntegralInRange<int>(0, n + 5);
    AFNParamInfo info {};
    if (pick < n && afnGetFilterTypeParam(method.c_str(), pick, &info))
        return info.name;
    static const char* const extra[]
        = { "stats.nonFinite", "stats.negative", "frameIndex", "width", "height" };
    if (pick - n < 5)
        return extra[pick - n];
    return in.ConsumeRandomLengthString(24);
}

/// Bind an image of fuzzed format, size and strides (any byte offset and stride, negative and
/// overlapping rows included), the buffer filled with fuzzed values.
void setImage(FuzzedDataProvider& in, AFNFilter f, std::map<std::string, Bound>& images)
{
    const std::string name = kImageNames[in.ConsumeIntegralInRange<int>(0, 8)];
    const int format = in.ConsumeIntegralInRange<int>(0, 5);
    const int ch = format >= 1 && format <= 4 ? format : 1;
    Bound b;
    b.width = in.ConsumeIntegralInRange<int>(0, 24);
    b.height = in.ConsumeIntegralInRange<int>(0, 24);
    b.channels = ch;
    const std::size_t offset = in.ConsumeIntegralInRange<std::size_t>(0, 12);
    const std::size_t pixel = in.ConsumeBool() ? 0 : in.ConsumeIntegralInRange<std::size_t>(0, 24);
    const std::size_t px = pixel ? pixel : 4 * static_cast<std::size_t>(ch);
    const std::size_t packedRow = px * static_cast<std::size_t>(b.width);
    const int rowMode = in.ConsumeIntegralInRange<int>(0, 2); // packed, positive, negative
    const std::size_t rowAbs = in.ConsumeIntegralInRange<std::size_t>(0, packedRow + 12);
    const std::ptrdiff_t row
        = rowMode == 0 ? 0 : static_cast<std::ptrdiff_t>(rowAbs) * (rowMode == 1 ? 1 : -1);
    const std::size_t rowBytes = row ? rowAbs : packedRow; // as the API resolves a 0 stride
    // Bytes the description covers: from the lowest row start to the end of the last pixel.
    std::size_t span = offset;
    if (b.width > 0 && b.height > 0)
        span += rowBytes * static_cast<std::size_t>(b.height - 1)
            + px * static_cast<std::size_t>(b.width - 1) + 4 * static_cast<std::size_t>(ch);
    b.bytes.resize(span);
    for (std::size_t i = 0; i + 4 <= b.bytes.size(); i += 4) {
        const float v = in.remaining_bytes() ? anyFloat(in) : 0.5f;
        std::memcpy(&b.bytes[i], &v, 4);
    }
    unsigned char* base = b.bytes.empty() ? nullptr : b.bytes.data();
    if (base && row < 0 && b.height > 0)
        base += rowBytes * static_cast<std::size_t>(b.height - 1); // row 0 is the last in memory
    b.ptr = in.ConsumeIntegralInRange<int>(0, 15) == 0 ? nullptr : base;
    b.pixelStride = px;
    b.rowStride = row ? row : static_cast<std::ptrdiff_t>(packedRow);
    afnSetFilterImage(f, name.c_str(), b.ptr, static_cast<AFNFormat>(format), b.width, b.height,
        offset, pixel, row);
    if (fuzz::takeError(g_device, kTarget) == AFN_ERROR_NONE) {
        b.ptr = b.ptr ? static_cast<unsigned char*>(b.ptr) + offset : nullptr;
        images[name] = std::move(b); // kept alive while bound
    }
}

/// Every value of the bound output (first three channels and alpha) is finite.
void checkOutput(const std::map<std::string, Bound>& images)
{
    auto it = images.find("output");
    if (it == images.end())
        return;
    const Bound& o = it->second;
    for (int y = 0; y < o.height; ++y)
        for (int x = 0; x < o.width; ++x)
            for (int c = 0; c < o.channels; ++c)
                fuzz::check(std::isfinite(o.value(x, y, c)), kTarget,
                    "non-finite output at " + std::to_string(x) + "," + std::to_string(y));
}

void step(FuzzedDataProvider& in, const std::string& method, AFNFilter f,
    std::map<std::string, Bound>& images)
{
    switch (in.ConsumeIntegralInRange<int>(0, 11)) {
    case 0:
        afnSetFilterBool(f, paramName(in, method).c_str(), in.ConsumeBool());
        break;
    case 1:
        afnSetFilterInt(f, paramName(in, method).c_str(), in.ConsumeIntegral<int>());
        break;
    case 2: {
        const std::string n = paramName(in, method);
        afnSetFilterFloat(f, n.c_str(), anyFloat(in));
        break;
    }
    case 3: {
        const std::string n = paramName(in, method);
        const std::string v = in.ConsumeRandomLengthString(32);
        afnSetFilterString(
            f, n.c_str(), in.ConsumeIntegralInRange<int>(0, 20) ? v.c_str() : nullptr);
        break;
    }
    case 4: {
        static const char* const names[] = { "viewProjection", "pixelOffset", "other" };
        std::vector<float> v(in.ConsumeIntegralInRange<std::size_t>(0, 17));
        for (float& x : v)
            x = anyFloat(in);
        afnSetFilterFloats(f, names[in.ConsumeIntegralInRange<int>(0, 2)], v.data(), v.size());
        break;
    }
    case 5: {
        const std::string blob = in.ConsumeRandomLengthString(64);
        afnSetFilterData(f, in.ConsumeBool() ? "weights" : "other", blob.data(), blob.size());
        break;
    }
    case 6:
    case 7:
        setImage(in, f, images);
        break;
    case 8: {
        const std::string name = kImageNames[in.ConsumeIntegralInRange<int>(0, 8)];
        afnUnsetFilterImage(f, name.c_str());
        if (fuzz::takeError(g_device, kTarget) == AFN_ERROR_NONE)
            images.erase(name);
        break;
    }
    case 9:
        afnCommitFilter(f);
        break;
    case 10:
        afnExecuteFilter(f);
        if (fuzz::takeError(g_device, kTarget) == AFN_ERROR_NONE)
            checkOutput(images);
        break;
    default: {
        const std::string n = paramName(in, method);
        switch (in.ConsumeIntegralInRange<int>(0, 4)) {
        case 0:
            afnGetFilterBool(f, n.c_str());
            break;
        case 1:
            afnGetFilterInt(f, n.c_str());
            break;
        case 2:
            afnGetFilterFloat(f, n.c_str());
            break;
        case 3:
            afnGetFilterString(f, n.c_str());
            break;
        default:
            afnResetFilter(f);
        }
    }
    }
    fuzz::takeError(g_device, kTarget);
}

} // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***)
{
    g_device = fuzz::newSingleThreadDevice();
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
    FuzzedDataProvider in(data, size);
    const int n = afnGetNumFilterTypes();
    const int pick = in.ConsumeIntegralInRange<int>(0, n);
    const std::string method
        = pick < n ? afnGetFilterTypeName(pick) : in.ConsumeRandomLengthString(16);
    AFNFilter f = afnNewFilter(g_device, method.c_str());
    fuzz::takeError(g_device, kTarget);
    if (!f)
        return 0;
    std::map<std::string, Bound> images;
    for (int i = 0; i < 48 && in.remaining_bytes(); ++i)
        step(in, method, f, images);
    afnReleaseFilter(f);
    fuzz::takeError(g_device, kTarget);
    return 0;
}
