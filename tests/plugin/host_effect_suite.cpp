// SPDX-License-Identifier: Apache-2.0
// The test host's image-effect suite: clips, images at render scale with the host's layout,
// frames-needed enforcement, abort and image memory.
#include "ofx_test_host.h"

#include <cmath>
#include <cstring>
#include <limits>

namespace ofxhost {

RenderTarget*& currentRenderTarget()
{
    thread_local RenderTarget* target = nullptr;
    return target;
}

OfxPropertySetStruct* makeImage(const std::vector<float>* frame, const OfxRectI& frameBounds,
    const OfxRectI& bounds, int components, double scale, const Layout& layout)
{
    const int w = bounds.x2 - bounds.x1, h = bounds.y2 - bounds.y1, c = components;
    const size_t rowFloats = size_t(w + layout.rowPaddingPixels) * c;
    auto memory = std::make_shared<std::vector<float>>(
        rowFloats * std::max(h, 1), std::numeric_limits<float>::quiet_NaN());
    // Memory row of pixel row y: bottom-up, or top-down when row bytes are negative.
    auto rowOf = [&](int y) {
        const int r = layout.negativeRowBytes ? bounds.y2 - 1 - y : y - bounds.y1;
        return memory->data() + size_t(r) * rowFloats;
    };
    if (frame) {
        const int fw = frameBounds.x2 - frameBounds.x1;
        for (int y = bounds.y1; y < bounds.y2; ++y)
            for (int x = bounds.x1; x < bounds.x2; ++x) {
                const float* src = frame->data()
                    + (size_t(frameBounds.y2 - 1 - y) * fw + (x - frameBounds.x1)) * c;
                std::memcpy(rowOf(y) + size_t(x - bounds.x1) * c, src, c * sizeof(float));
            }
    }
    auto* img = new OfxPropertySetStruct;
    img->owned = memory;
    img->setPointer(kOfxImagePropData, h > 0 ? rowOf(bounds.y1) : memory->data());
    img->setInts(kOfxImagePropBounds, { bounds.x1, bounds.y1, bounds.x2, bounds.y2 });
    const int rowBytes = int(rowFloats * sizeof(float));
    img->setInts(kOfxImagePropRowBytes, { layout.negativeRowBytes ? -rowBytes : rowBytes });
    img->setStrings(kOfxImageEffectPropComponents,
        { c == 4         ? kOfxImageComponentRGBA
                : c == 3 ? kOfxImageComponentRGB
                         : kOfxImageComponentAlpha });
    img->setStrings(kOfxImageEffectPropPixelDepth, { kOfxBitDepthFloat });
    img->setDoubles(kOfxImagePropPixelAspectRatio, { 1.0 });
    img->setInts(kOfxImagePropRegionOfDefinition,
        { frameBounds.x1, frameBounds.y1, frameBounds.x2, frameBounds.y2 });
    img->setDoubles(kOfxImageEffectPropRenderScale, { scale, scale });
    img->setStrings(kOfxImagePropField, { kOfxImageFieldNone });
    img->setStrings(kOfxImagePropUniqueIdentifier, { "img" });
    img->setStrings(kOfxImageEffectPropPreMultiplication, { kOfxImageUnPreMultiplied });
    return img;
}

namespace {

OfxRectI pixelRod(const ClipSource& s, double scale)
{
    return { int(std::lround(s.originX * scale)), int(std::lround(s.originY * scale)),
        int(std::lround((s.originX + s.width) * scale)),
        int(std::lround((s.originY + s.height) * scale)) };
}

const ClipSource* sourceOf(OfxImageClipHandle clip)
{
    if (clip->source)
        return clip->source;
    if (clip->name == kOfxImageEffectOutputClipName && clip->effect) {
        OfxImageClipStruct* src = clip->effect->clip(kOfxImageEffectSimpleSourceClipName);
        return src ? src->source : nullptr;
    }
    return nullptr;
}

OfxStatus getPropertySet(OfxImageEffectHandle e, OfxPropertySetHandle* p)
{
    if (!e || !p)
        return kOfxStatErrBadHandle;
    *p = &e->props;
    return kOfxStatOK;
}

OfxStatus getParamSet(OfxImageEffectHandle e, OfxParamSetHandle* p)
{
    if (!e || !p)
        return kOfxStatErrBadHandle;
    *p = &e->params;
    return kOfxStatOK;
}

OfxStatus clipDefine(OfxImageEffectHandle e, const char* name, OfxPropertySetHandle* p)
{
    if (!e || !name)
        return kOfxStatErrBadHandle;
    if (e->clip(name))
        return kOfxStatErrExists;
    auto clip = std::make_unique<OfxImageClipStruct>();
    clip->name = name;
    clip->effect = e;
    clip->props.setStrings(kOfxPropName, { name });
    clip->props.setInts(kOfxImageClipPropOptional, { 0 });
    if (p)
        *p = &clip->props;
    e->clips.push_back(std::move(clip));
    return kOfxStatOK;
}

OfxStatus clipGetHandle(
    OfxImageEffectHandle e, const char* name, OfxImageClipHandle* c, OfxPropertySetHandle* p)
{
    if (!e || !name || !c)
        return kOfxStatErrBadHandle;
    OfxImageClipStruct* clip = e->clip(name);
    if (!clip)
        return kOfxStatErrUnknown;
    *c = clip;
    if (p)
        *p = &clip->props;
    return kOfxStatOK;
}

OfxStatus clipGetPropertySet(OfxImageClipHandle c, OfxPropertySetHandle* p)
{
    if (!c || !p)
        return kOfxStatErrBadHandle;
    *p = &c->props;
    return kOfxStatOK;
}

bool frameDeclared(OfxImageClipHandle clip, double time, const RenderTarget& target)
{
    if (time == target.time)
        return true;
    const auto it = target.framesNeeded.find(clip->name);
    if (it == target.framesNeeded.end())
        return false;
    for (size_t i = 0; i + 1 < it->second.size(); i += 2)
        if (time >= it->second[i] && time <= it->second[i + 1])
            return true;
    return false;
}

OfxStatus clipGetImage(
    OfxImageClipHandle clip, OfxTime time, const OfxRectD* region, OfxPropertySetHandle* image)
{
    if (!clip || !image)
        return kOfxStatErrBadHandle;
    RenderTarget* target = currentRenderTarget();
    Host* host = clip->effect ? clip->effect->host : nullptr;
    if (!host)
        return kOfxStatErrBadHandle;
    if (clip->name == kOfxImageEffectOutputClipName) {
        if (!target || target->instance != clip->effect || time != target->time)
            return kOfxStatFailed;
        *image = new OfxPropertySetStruct(*target->image); // shares the target's memory
        (*image)->imageHost = host;
        ++host->m_liveImages;
        return kOfxStatOK;
    }
    const ClipSource* src = clip->source;
    if (!src)
        return kOfxStatFailed;
    const double scale = target ? target->scale : 1.0;
    if (target && !frameDeclared(clip, time, *target)) {
        host->addMessage("host: frame " + std::to_string(time) + " of clip " + clip->name
            + " was not declared in GetFramesNeeded");
        return kOfxStatFailed;
    }
    std::vector<float> pixels;
    if (!src->frame(time, scale, pixels))
        return kOfxStatFailed;
    const OfxRectI rod = pixelRod(*src, scale);
    OfxRectI b = rod;
    if (region) {
        b = { std::max(rod.x1, int(std::floor(region->x1 * scale))),
            std::max(rod.y1, int(std::floor(region->y1 * scale))),
            std::min(rod.x2, int(std::ceil(region->x2 * scale))),
            std::min(rod.y2, int(std::ceil(region->y2 * scale))) };
    }
    *image = makeImage(&pixels, rod, b, src->components, scale, host->layout());
    (*image)->imageHost = host;
    {
        std::lock_guard<std::mutex> lock(clip->framesMutex);
        clip->fetched.push_back(time);
    }
    ++host->m_liveImages;
    return kOfxStatOK;
}

OfxStatus clipReleaseImage(OfxPropertySetHandle image)
{
    if (!image)
        return kOfxStatErrBadHandle;
    if (image->imageHost)
        --image->imageHost->m_liveImages;
    delete image;
    return kOfxStatOK;
}

OfxStatus clipGetRegionOfDefinition(OfxImageClipHandle clip, OfxTime, OfxRectD* rod)
{
    if (!clip || !rod)
        return kOfxStatErrBadHandle;
    const ClipSource* s = sourceOf(clip);
    if (!s)
        return kOfxStatFailed;
    *rod = { double(s->originX), double(s->originY), double(s->originX + s->width),
        double(s->originY + s->height) };
    return kOfxStatOK;
}

int abortRender(OfxImageEffectHandle e)
{
    return e && e->host && e->host->abortFlag.load();
}

} // namespace

} // namespace ofxhost

std::vector<double> OfxImageClipStruct::takeFetched()
{
    std::lock_guard<std::mutex> lock(framesMutex);
    std::vector<double> out;
    out.swap(fetched);
    return out;
}

struct OfxImageMemoryStruct {
    std::vector<char> bytes;
};

namespace ofxhost {

namespace {

OfxStatus memAlloc(OfxImageEffectHandle, size_t n, OfxImageMemoryHandle* m)
{
    if (!m)
        return kOfxStatErrBadHandle;
    *m = new OfxImageMemoryStruct { std::vector<char>(n) };
    return kOfxStatOK;
}
OfxStatus memFree(OfxImageMemoryHandle m)
{
    delete m;
    return kOfxStatOK;
}
OfxStatus memLock(OfxImageMemoryHandle m, void** p)
{
    if (!m || !p)
        return kOfxStatErrBadHandle;
    *p = m->bytes.data();
    return kOfxStatOK;
}
OfxStatus memUnlock(OfxImageMemoryHandle m)
{
    return m ? kOfxStatOK : kOfxStatErrBadHandle;
}

} // namespace

const OfxImageEffectSuiteV1* imageEffectSuite()
{
    static const OfxImageEffectSuiteV1 suite = {
        getPropertySet,
        getParamSet,
        clipDefine,
        clipGetHandle,
        clipGetPropertySet,
        clipGetImage,
        clipReleaseImage,
        clipGetRegionOfDefinition,
        abortRender,
        memAlloc,
        memFree,
        memLock,
        memUnlock,
    };
    return &suite;
}

} // namespace ofxhost
