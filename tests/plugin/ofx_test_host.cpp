// SPDX-License-Identifier: Apache-2.0
// The test host's life cycle: loading, describing, instances, parameters and frame renders.
#include "ofx_test_host.h"

#include <dlfcn.h>

#include <cmath>
#include <cstring>

OfxParamStruct* OfxParamSetStruct::find(const std::string& name) const
{
    for (const auto& p : params)
        if (p->name == name)
            return p.get();
    return nullptr;
}

OfxImageClipStruct* OfxImageEffectStruct::clip(const std::string& name) const
{
    for (const auto& c : clips)
        if (c->name == name)
            return c.get();
    return nullptr;
}

namespace ofxhost {

namespace {

void copyDescriptor(const OfxImageEffectStruct& from, OfxImageEffectStruct& to)
{
    to.props = from.props;
    to.params.props = from.params.props;
    for (const auto& p : from.params.params) {
        auto q = std::make_unique<OfxParamStruct>();
        q->props = p->props;
        q->type = p->type;
        q->name = p->name;
        to.params.params.push_back(std::move(q));
    }
    for (const auto& c : from.clips) {
        auto d = std::make_unique<OfxImageClipStruct>();
        d->props = c->props;
        d->name = c->name;
        d->effect = &to;
        to.clips.push_back(std::move(d));
    }
}

const char* componentsName(int c)
{
    return c == 4 ? kOfxImageComponentRGBA
        : c == 3  ? kOfxImageComponentRGB
                  : kOfxImageComponentAlpha;
}

} // namespace

Host::Host(Layout layout)
    : m_layout(layout)
{
    hostProps.setStrings(kOfxPropName, { "org.afn.TestHost" });
    hostProps.setStrings(kOfxPropLabel, { "afn test host" });
    hostProps.setInts(kOfxImageEffectPropSupportsTiles, { 1 });
    hostProps.setInts(kOfxImageEffectPropTemporalClipAccess, { 1 });
    hostProps.setInts(kOfxImageEffectPropSupportsMultiResolution, { 1 });
    hostProps.setInts(kOfxImageEffectPropSupportsMultipleClipDepths, { 0 });
    hostProps.setStrings(kOfxImageEffectPropSupportedContexts,
        { kOfxImageEffectContextFilter, kOfxImageEffectContextGeneral });
    hostProps.setStrings(kOfxImageEffectPropSupportedPixelDepths, { kOfxBitDepthFloat });
    hostProps.setStrings(kOfxImageEffectPropSupportedComponents,
        { kOfxImageComponentRGBA, kOfxImageComponentRGB, kOfxImageComponentAlpha });
    m_ofxHost.host = &hostProps;
    m_ofxHost.fetchSuite = fetchSuite;
}

Host::~Host()
{
    if (m_library)
        dlclose(m_library);
}

bool Host::load(const std::string& path, std::string* error)
{
    m_library = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (!m_library) {
        if (error)
            *error = std::string("dlopen: ") + dlerror();
        return false;
    }
    auto count = reinterpret_cast<int (*)()>(dlsym(m_library, "OfxGetNumberOfPlugins"));
    auto get = reinterpret_cast<OfxPlugin* (*)(int)>(dlsym(m_library, "OfxGetPlugin"));
    if (!count || !get) {
        if (error)
            *error = path + " lacks OfxGetNumberOfPlugins/OfxGetPlugin";
        return false;
    }
    m_numPlugins = count();
    m_plugin = m_numPlugins > 0 ? get(0) : nullptr;
    if (!m_plugin && error)
        *error = path + " has no plugin";
    return m_plugin != nullptr;
}

OfxStatus Host::action(const char* name, const void* handle, OfxPropertySetStruct* inArgs,
    OfxPropertySetStruct* outArgs)
{
    return m_plugin->mainEntry(name, handle, inArgs, outArgs);
}

OfxStatus Host::describe()
{
    m_plugin->setHost(&m_ofxHost);
    if (OfxStatus s = action(kOfxActionLoad, nullptr, nullptr, nullptr);
        s != kOfxStatOK && s != kOfxStatReplyDefault)
        return s;
    m_descriptor = std::make_unique<OfxImageEffectStruct>();
    m_descriptor->host = this;
    return action(kOfxActionDescribe, m_descriptor.get(), nullptr, nullptr);
}

OfxStatus Host::describeInContext(
    const std::string& context, std::unique_ptr<OfxImageEffectStruct>& out)
{
    out = std::make_unique<OfxImageEffectStruct>();
    copyDescriptor(*m_descriptor, *out);
    out->host = this;
    OfxPropertySetStruct in;
    in.setStrings(kOfxImageEffectPropContext, { context });
    return action(kOfxImageEffectActionDescribeInContext, out.get(), &in, nullptr);
}

std::unique_ptr<OfxImageEffectStruct> Host::createInstance(const OfxImageEffectStruct& desc,
    const std::string& context, const std::map<std::string, const ClipSource*>& inputs,
    OfxStatus* status)
{
    auto inst = std::make_unique<OfxImageEffectStruct>();
    copyDescriptor(desc, *inst);
    inst->host = this;
    inst->props.setStrings(kOfxImageEffectPropContext, { context });
    inst->props.setPointer(kOfxPropInstanceData, nullptr);
    for (const auto& p : inst->params.params) {
        const auto it = p->props.props.find(kOfxParamPropDefault);
        if (it == p->props.props.end())
            continue;
        if (it->second.type == Prop::Int && !it->second.i.empty())
            p->intValue = it->second.i[0];
        if (it->second.type == Prop::Double && !it->second.d.empty())
            p->doubleValue = it->second.d[0];
        if (it->second.type == Prop::String && !it->second.s.empty())
            p->stringValue = it->second.s[0];
    }
    const auto sourceIt = inputs.find(kOfxImageEffectSimpleSourceClipName);
    for (const auto& c : inst->clips) {
        const auto it = inputs.find(c->name);
        c->source = it == inputs.end() ? nullptr : it->second;
        const bool output = c->name == kOfxImageEffectOutputClipName;
        const ClipSource* range = output && sourceIt != inputs.end() ? sourceIt->second : c->source;
        c->props.setInts(kOfxImageClipPropConnected, { c->source || output ? 1 : 0 });
        c->props.setDoubles(kOfxImageEffectPropFrameRange,
            { range ? range->firstFrame : 0.0, range ? range->lastFrame : 0.0 });
        c->props.setStrings(kOfxImageEffectPropComponents,
            { componentsName(c->source ? c->source->components : 4) });
        c->props.setStrings(kOfxImageEffectPropPixelDepth, { kOfxBitDepthFloat });
        c->props.setDoubles(kOfxImagePropPixelAspectRatio, { 1.0 });
        c->props.setStrings(kOfxImageEffectPropPreMultiplication, { kOfxImageUnPreMultiplied });
    }
    OfxPropertySetStruct in;
    *status = action(kOfxActionCreateInstance, inst.get(), &in, nullptr);
    return inst;
}

OfxStatus Host::destroyInstance(OfxImageEffectStruct* instance)
{
    return action(kOfxActionDestroyInstance, instance, nullptr, nullptr);
}

OfxStatus Host::unload()
{
    const OfxStatus s = action(kOfxActionUnload, nullptr, nullptr, nullptr);
    m_descriptor.reset();
    return s;
}

namespace {

OfxStatus instanceChanged(Host& host, OfxImageEffectStruct* instance, const std::string& name)
{
    OfxPropertySetStruct in;
    in.setStrings(kOfxPropType, { kOfxTypeParameter });
    in.setStrings(kOfxPropName, { name });
    in.setStrings(kOfxPropChangeReason, { "OfxChangeUserEdited" });
    in.setDoubles(kOfxPropTime, { 0.0 });
    in.setDoubles(kOfxImageEffectPropRenderScale, { 1.0, 1.0 });
    const OfxStatus s = host.action(kOfxActionInstanceChanged, instance, &in, nullptr);
    return s == kOfxStatReplyDefault ? kOfxStatOK : s;
}

} // namespace

OfxStatus Host::setParam(OfxImageEffectStruct* instance, const std::string& name, double value)
{
    OfxParamStruct* p = instance->params.find(name);
    if (!p || p->type == kOfxParamTypeString || p->type == kOfxParamTypeGroup)
        return kOfxStatErrUnknown;
    if (p->type == kOfxParamTypeDouble)
        p->doubleValue = value;
    else
        p->intValue = static_cast<int>(value);
    return instanceChanged(*this, instance, name);
}

OfxStatus Host::setParam(
    OfxImageEffectStruct* instance, const std::string& name, const std::string& value)
{
    OfxParamStruct* p = instance->params.find(name);
    if (!p || p->type != kOfxParamTypeString)
        return kOfxStatErrUnknown;
    p->stringValue = value;
    return instanceChanged(*this, instance, name);
}

void Host::addMessage(const std::string& m)
{
    std::lock_guard<std::mutex> lock(m_messagesMutex);
    m_messages.push_back(m);
}

std::vector<std::string> Host::messages() const
{
    std::lock_guard<std::mutex> lock(m_messagesMutex);
    return m_messages;
}

OfxStatus Host::renderFrame(
    OfxImageEffectStruct* inst, double time, double scale, int tiles, Frame& out)
{
    OfxPropertySetStruct timeArgs;
    timeArgs.setDoubles(kOfxPropTime, { time });
    timeArgs.setDoubles(kOfxImageEffectPropRenderScale, { scale, scale });

    OfxPropertySetStruct rodOut;
    OfxStatus s = action(kOfxImageEffectActionGetRegionOfDefinition, inst, &timeArgs, &rodOut);
    if (s != kOfxStatOK)
        return s == kOfxStatReplyDefault ? kOfxStatFailed : s;
    const Prop& r = rodOut.props.at(kOfxImageEffectPropRegionOfDefinition);
    const OfxRectI rod = { int(std::floor(r.d.at(0) * scale)), int(std::floor(r.d.at(1) * scale)),
        int(std::ceil(r.d.at(2) * scale)), int(std::ceil(r.d.at(3) * scale)) };
    const int w = rod.x2 - rod.x1, h = rod.y2 - rod.y1;
    out.bounds = rod;
    out.rgba.assign(size_t(w) * h * 4, std::nanf(""));

    // Frames needed (the host refuses images at other times from now on).
    OfxPropertySetStruct framesOut;
    s = action(kOfxImageEffectActionGetFramesNeeded, inst, &timeArgs, &framesOut);
    if (s != kOfxStatOK && s != kOfxStatReplyDefault)
        return s;
    std::map<std::string, std::vector<double>> framesNeeded;
    for (const auto& c : inst->clips) {
        auto it = framesOut.props.find(kOfxImageClipPropFrameRange + c->name);
        framesNeeded[c->name] = it == framesOut.props.end() ? std::vector<double> {} : it->second.d;
        std::lock_guard<std::mutex> lock(c->framesMutex);
        c->framesNeeded = framesNeeded[c->name];
    }

    for (int ty = 0; ty < tiles; ++ty)
        for (int tx = 0; tx < tiles; ++tx) {
            // Uneven tiles: the first column and row are narrower.
            const OfxRectI win = { rod.x1 + (w * tx) / tiles - (tx > 0 ? 1 : 0),
                rod.y1 + (h * ty) / tiles - (ty > 0 ? 1 : 0),
                tx + 1 == tiles ? rod.x2 : rod.x1 + (w * (tx + 1)) / tiles - 1,
                ty + 1 == tiles ? rod.y2 : rod.y1 + (h * (ty + 1)) / tiles - 1 };
            OfxPropertySetStruct roiIn = timeArgs, roiOut;
            roiIn.setDoubles(kOfxImageEffectPropRegionOfInterest,
                { win.x1 / scale, win.y1 / scale, win.x2 / scale, win.y2 / scale });
            s = action(kOfxImageEffectActionGetRegionsOfInterest, inst, &roiIn, &roiOut);
            if (s != kOfxStatOK && s != kOfxStatReplyDefault)
                return s;
            for (const auto& c : inst->clips) {
                auto it = roiOut.props.find(kOfxImageClipPropRoI + c->name);
                std::lock_guard<std::mutex> lock(c->framesMutex);
                c->lastRoI = it == roiOut.props.end() ? std::vector<double> {} : it->second.d;
            }

            std::unique_ptr<OfxPropertySetStruct> image(
                makeImage(nullptr, rod, win, 4, scale, m_layout));
            RenderTarget target { inst, time, scale, win, image.get(), framesNeeded };
            currentRenderTarget() = &target;
            OfxPropertySetStruct in = timeArgs;
            in.setStrings(kOfxImageEffectPropFieldToRender, { kOfxImageFieldNone });
            in.setInts(kOfxImageEffectPropRenderWindow, { win.x1, win.y1, win.x2, win.y2 });
            in.setInts(kOfxImageEffectPropSequentialRenderStatus, { 0 });
            s = action(kOfxImageEffectActionRender, inst, &in, nullptr);
            currentRenderTarget() = nullptr;
            if (s != kOfxStatOK)
                return s;
            // Stitch: read the tile through its own data pointer and row bytes.
            const char* data = static_cast<const char*>(image->getPointer(kOfxImagePropData));
            const int rowBytes = image->getInt(kOfxImagePropRowBytes);
            for (int y = win.y1; y < win.y2; ++y)
                for (int x = win.x1; x < win.x2; ++x) {
                    const float* src = reinterpret_cast<const float*>(
                        data + std::ptrdiff_t(y - win.y1) * rowBytes + (x - win.x1) * 16);
                    std::memcpy(
                        &out.rgba[(size_t(rod.y2 - 1 - y) * w + (x - rod.x1)) * 4], src, 16);
                }
        }
    return kOfxStatOK;
}

} // namespace ofxhost
