// SPDX-License-Identifier: Apache-2.0
// Conversion of caller buffers into the canonical Frame (conventions in filter/frame.h).
//
// Sanitising rule (documented in docs/afntool.md, counted in InputStats):
//   - NaN or +-Inf in any input is replaced by 0 (in the albedo by 1: unknown, no demodulation).
//   - Negative colour is clamped to 0 (radiance cannot be negative; renderers' negative lobes and
//     filter ringing would otherwise feed the history).
//   - Albedo is clamped to [0, 1]; normals are renormalised (a zero normal stays zero and then
//     never matches history).
#include "filter/filter.h"

#include "base/exception.h"
#include "base/parallel.h"
#include "cpu/isa.h"
#include "filter/gather_avx512.h"

#include <atomic>
#include <cfloat>
#include <cmath>
#include <type_traits>

namespace afn {

namespace {

struct Counters {
    std::atomic<std::int64_t> nonFinite { 0 };
    std::atomic<std::int64_t> negative { 0 };
};

/// Copy `channels` channels of a binding into `dst` through gatherValue (non-finite values become
/// op.replacement, then op's per-value operation), then `perRow(float* row, int width)` converts
/// each packed row in place. A binding whose pixels are packed with exactly `channels` floats (the
/// usual case) is copied row by row as one run of floats, with AVX-512F where the CPU has it.
template <typename PerRow>
void gather(const ImageBinding& b, int channels, Image& dst, Counters& counts, const GatherOp& op,
    PerRow&& perRow)
{
    // Rows converted in place right after their copy stay in cache (no streaming stores).
    constexpr bool stream = std::is_same_v<std::decay_t<PerRow>, void (*)(float*, int)>;
    const ImageView src = b.view();
    dst.resize(src.width, src.height, channels);
    const bool packed = src.channels == channels
        && src.pixelStride == static_cast<std::ptrdiff_t>(channels * sizeof(float));
    const bool avx512 = cpu::activeIsa() == cpu::Isa::Avx512;
    parallelRows(src.height, [&](int y0, int y1) {
        GatherCounts local;
        for (int y = y0; y < y1; ++y) {
            float* d = dst.at(0, y);
            if (packed && avx512) {
                gatherRunAvx512(src.at(0, y), d, src.width * channels, op, local, stream);
            } else if (packed) {
                const float* s = src.at(0, y);
                const int n = src.width * channels;
                for (int i = 0; i < n; ++i)
                    d[i] = gatherValue(s[i], i % channels, op, local);
            } else {
                for (int x = 0; x < src.width; ++x) {
                    const float* s = src.at(x, y);
                    for (int c = 0; c < channels; ++c)
                        d[x * channels + c]
                            = gatherValue(c < src.channels ? s[c] : 0.0f, c, op, local);
                }
            }
            perRow(d, src.width);
        }
        counts.nonFinite += local.nonFinite;
        counts.negative += local.negative;
    });
}

void noRowConversion(float*, int) { }

const ImageBinding* find(const std::map<std::string, ImageBinding>& m, const char* name)
{
    auto it = m.find(name);
    return it == m.end() ? nullptr : &it->second;
}

} // namespace

void gatherFrame(const std::map<std::string, ImageBinding>& images,
    const InputConventions& conventions, Frame& f, InputStats& stats)
{
    Counters counts;
    const ImageBinding* color = find(images, AFN_IMAGE_COLOR);
    if (!color)
        throwInvalidOperation("no 'color' image set");
    f.width = color->width;
    f.height = color->height;

    gather(*color, 3, f.color, counts, { GatherOp::Kind::NonNegative }, noRowConversion);

    // A non-finite albedo is unknown and becomes 1 (no demodulation): 0 would divide the colour by
    // the albedo floor and carry it, amplified 1024x, into the filters and the history.
    // The clamp is std::fmin(std::fmax(p, 0), 1) for the finite values (-0 stays -0, as glibc's
    // fmaxf(-0, 0) gives), without the two libm calls per channel (GatherOp::Kind::Unit).
    if (const ImageBinding* b = find(images, AFN_IMAGE_ALBEDO))
        gather(*b, 3, f.albedo, counts, { GatherOp::Kind::Unit, 1.0f }, noRowConversion);
    else
        f.albedo = Image();

    using Normals = InputConventions::Normals;
    const float zSign = conventions.normalSpace == Normals::CameraTowardViewer ? -1.0f : 1.0f;
    f.normalSpace
        = conventions.normalSpace == Normals::World ? NormalSpace::World : NormalSpace::Camera;
    if (const ImageBinding* b = find(images, AFN_IMAGE_NORMAL))
        gather(*b, 3, f.normal, counts, {}, [zSign](float* row, int width) {
            int x = 0;
            if (cpu::activeIsa() == cpu::Isa::Avx512) // 16 at a time, the same operations
                for (; x + 16 <= width; x += 16)
                    normalizeNormals16(row + 3 * x, zSign);
            for (; x < width; ++x) {
                float* p = row + 3 * x;
                p[2] *= zSign;
                const float len = std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
                const float inv = len > 1e-12f ? 1.0f / len : 0.0f;
                for (int c = 0; c < 3; ++c)
                    p[c] *= inv;
            }
        });
    else
        f.normal = Image();

    f.depthKind = conventions.depthKind;
    if (const ImageBinding* b = find(images, AFN_IMAGE_DEPTH))
        gather(*b, 1, f.depth, counts, {}, noRowConversion);
    else
        f.depth = Image();

    if (const ImageBinding* b = find(images, AFN_IMAGE_POSITION))
        gather(*b, 3, f.position, counts, {}, noRowConversion);
    else
        f.position = Image();

    if (const ImageBinding* b = find(images, AFN_IMAGE_MOTION)) {
        // To canonical: pixels, y down, pointing to the previous frame.
        using Units = InputConventions::MotionUnits;
        float sx = conventions.motionScale, sy = sx;
        if (conventions.motionUnits == Units::Ndc) {
            sx *= 0.5f * f.width;
            sy *= 0.5f * f.height;
        } else if (conventions.motionUnits == Units::Uv) {
            sx *= f.width;
            sy *= f.height;
        }
        if (conventions.motionYUp)
            sy = -sy;
        if (conventions.motionDirection == InputConventions::MotionDirection::ToNext) {
            // Constant-velocity assumption: the offset to the previous frame is minus the offset to
            // the next one.
            sx = -sx;
            sy = -sy;
        }
        gather(*b, 2, f.motion, counts, { GatherOp::Kind::Scale2, 0.0f, sx, sy }, noRowConversion);
    } else {
        f.motion = Image();
    }

    if (const ImageBinding* b = find(images, AFN_IMAGE_ALPHA)) {
        // A FLOAT4 alpha binding (e.g. an RGBA beauty) carries alpha in its 4th channel.
        ImageBinding a = *b;
        if (a.channels() == 4) {
            a.byteOffset += 3 * sizeof(float);
            a.format = AFN_FORMAT_FLOAT;
        }
        gather(a, 1, f.alpha, counts, {}, noRowConversion);
    } else {
        f.alpha = Image();
    }

    f.colorDemodulated = conventions.colorDemodulated;
    stats.nonFinite = counts.nonFinite;
    stats.negative = counts.negative;
}

} // namespace afn
