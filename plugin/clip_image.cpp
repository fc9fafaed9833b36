// SPDX-License-Identifier: Apache-2.0
#include "clip_image.h"

#include "ofx_support.h"

#include <algorithm>
#include <cstring>
#include <string>

namespace afnofx {

ClipImage::ClipImage(OfxImageClipHandle clip, double time, const OfxRectD* region)
{
    if (suites().effect->clipGetImage(clip, time, region, &m_handle) != kOfxStatOK) {
        m_handle = nullptr;
        return;
    }
    Props p(m_handle);
    m_data = static_cast<char*>(p.getPointer(kOfxImagePropData));
    m_rowBytes = p.getInt(kOfxImagePropRowBytes);
    m_bounds = { p.getInt(kOfxImagePropBounds, 0), p.getInt(kOfxImagePropBounds, 1),
        p.getInt(kOfxImagePropBounds, 2), p.getInt(kOfxImagePropBounds, 3) };
    const std::string depth = p.getString(kOfxImageEffectPropPixelDepth);
    if (depth != kOfxBitDepthFloat)
        throw OfxError(kOfxStatErrImageFormat, "image depth " + depth + " is not float");
    const std::string comps = p.getString(kOfxImageEffectPropComponents);
    m_components = comps == kOfxImageComponentRGBA ? 4
        : comps == kOfxImageComponentRGB           ? 3
        : comps == kOfxImageComponentAlpha         ? 1
                                                   : 0;
    if (m_components == 0)
        throw OfxError(kOfxStatErrImageFormat, "image components " + comps + " are not supported");
}

ClipImage::~ClipImage()
{
    if (m_handle)
        suites().effect->clipReleaseImage(m_handle);
}

float* ClipImage::pixel(int x, int y) const
{
    return reinterpret_cast<float*>(m_data + std::ptrdiff_t(y - m_bounds.y1) * m_rowBytes
        + std::ptrdiff_t(x - m_bounds.x1) * m_components * 4);
}

static bool covers(const OfxRectI& outer, const OfxRectI& inner)
{
    return outer.x1 <= inner.x1 && outer.y1 <= inner.y1 && outer.x2 >= inner.x2
        && outer.y2 >= inner.y2;
}

StridedView viewWindow(const ClipImage& image, const OfxRectI& window, std::vector<float>& scratch)
{
    StridedView v;
    v.components = image.components();
    v.pixelStride = size_t(v.components) * sizeof(float);
    if (covers(image.bounds(), window)) {
        // OFX rows run bottom-up: start at the window's top row and step down by -rowBytes.
        float* top = image.pixel(window.x1, window.y2 - 1);
        float* below = window.y2 - 1 > window.y1 ? image.pixel(window.x1, window.y2 - 2) : nullptr;
        v.ptr = top;
        v.rowStride = below ? reinterpret_cast<char*>(below) - reinterpret_cast<char*>(top)
                            : ptrdiff_t(v.pixelStride) * (window.x2 - window.x1);
        return v;
    }
    const int w = window.x2 - window.x1, h = window.y2 - window.y1, c = v.components;
    scratch.assign(size_t(w) * h * c, 0.0f);
    const OfxRectI& b = image.bounds();
    const int x0 = std::max(window.x1, b.x1), x1 = std::min(window.x2, b.x2);
    for (int y = std::max(window.y1, b.y1); y < std::min(window.y2, b.y2); ++y) {
        if (x0 >= x1)
            break;
        float* row = scratch.data() + (size_t(window.y2 - 1 - y) * w + (x0 - window.x1)) * c;
        std::memcpy(row, image.pixel(x0, y), size_t(x1 - x0) * c * sizeof(float));
    }
    v.ptr = scratch.data();
    v.rowStride = ptrdiff_t(w) * c * sizeof(float);
    return v;
}

namespace {

struct TileJob {
    const ClipImage* dst;
    OfxRectI rw;
    const float* frame;
    OfxRectI fw;
    const ClipImage* source; ///< NULL: no mix
    float mix;
};

bool inside(const OfxRectI& r, int x, int y)
{
    return x >= r.x1 && x < r.x2 && y >= r.y1 && y < r.y2;
}

/// mix * rgba + (1 - mix) * the source pixel at (x, y), in place.
void blend(const TileJob& j, int x, int y, float* rgba)
{
    const ClipImage& s = *j.source;
    const int sc = s.components();
    const float* sp = inside(s.bounds(), x, y) ? s.pixel(x, y) : nullptr;
    for (int i = 0; i < 4; ++i) {
        const float src = sp ? (i < sc ? sp[i] : rgba[i]) : (i < sc ? 0.0f : rgba[i]);
        rgba[i] = j.mix * rgba[i] + (1.0f - j.mix) * src;
    }
}

void writeRows(const TileJob& j, int yBegin, int yEnd)
{
    const int c = j.dst->components();
    const int fwWidth = j.fw.x2 - j.fw.x1;
    for (int y = yBegin; y < yEnd; ++y) {
        const bool rowInside = y >= j.fw.y1 && y < j.fw.y2;
        float* out = j.dst->pixel(j.rw.x1, y);
        for (int x = j.rw.x1; x < j.rw.x2; ++x, out += c) {
            if (rowInside && x >= j.fw.x1 && x < j.fw.x2) {
                const float* src
                    = j.frame + (size_t(j.fw.y2 - 1 - y) * fwWidth + (x - j.fw.x1)) * 4;
                float mixed[4];
                if (j.source) {
                    std::memcpy(mixed, src, sizeof(mixed));
                    blend(j, x, y, mixed);
                    src = mixed;
                }
                if (c == 1)
                    out[0] = src[3];
                else
                    std::memcpy(out, src, size_t(c) * sizeof(float));
            } else {
                std::fill(out, out + c, 0.0f);
            }
        }
    }
}

void writeSlice(unsigned int index, unsigned int count, void* arg)
{
    const TileJob& j = *static_cast<const TileJob*>(arg);
    const int h = j.rw.y2 - j.rw.y1;
    writeRows(
        j, j.rw.y1 + int(h * size_t(index) / count), j.rw.y1 + int(h * size_t(index + 1) / count));
}

} // namespace

void writeTile(const ClipImage& dst, const OfxRectI& renderWindow, const float* frameRgba,
    const OfxRectI& frame, const ClipImage* source, float mix)
{
    TileJob job { &dst, renderWindow, frameRgba, frame, source, mix };
    const OfxRectI& b = dst.bounds();
    job.rw = { std::max(renderWindow.x1, b.x1), std::max(renderWindow.y1, b.y1),
        std::min(renderWindow.x2, b.x2), std::min(renderWindow.y2, b.y2) };
    if (job.rw.x1 >= job.rw.x2 || job.rw.y1 >= job.rw.y2)
        return;
    unsigned int cpus = 1;
    const OfxMultiThreadSuiteV1* mt = suites().thread;
    if (mt && mt->multiThreadNumCPUs(&cpus) == kOfxStatOK && cpus > 1
        && mt->multiThread(writeSlice, std::min(cpus, unsigned(job.rw.y2 - job.rw.y1)), &job)
            == kOfxStatOK)
        return;
    writeRows(job, job.rw.y1, job.rw.y2);
}

} // namespace afnofx
