// SPDX-License-Identifier: Apache-2.0
#include "DenoiseEffect.h"

#include "clip_image.h"
#include "ofx_support.h"
#include "param_table.h"
#include "sequence_runner.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <mutex>

namespace afnofx {

namespace {

// Clip names (saved in projects: never rename) and the library image each one feeds.
struct ClipRole {
    const char* clip;
    const char* role;
};
const ClipRole kAuxClips[] = { { "Albedo", AFN_IMAGE_ALBEDO }, { "Normal", AFN_IMAGE_NORMAL },
    { "Depth", AFN_IMAGE_DEPTH }, { "Position", AFN_IMAGE_POSITION },
    { "Motion", AFN_IMAGE_MOTION },
    // Work skipping: pixels where the mask's first component (an Alpha clip's only one) is <= 0
    // need no denoising (docs/work-skipping.md; parameter "skip").
    { "Mask", AFN_IMAGE_MASK } };
constexpr int kNumAux = sizeof(kAuxClips) / sizeof(kAuxClips[0]);
// A light-path pass and its colour factor (version 1.2; docs/passes.md): read only when the
// Output choice is "pass".
const ClipRole kPassClips[] = { { "Pass", AFN_IMAGE_PASS_PREFIX "pass" },
    { "PassFactor", AFN_IMAGE_PASS_FACTOR_PREFIX "pass" } };
constexpr int kNumPass = sizeof(kPassClips) / sizeof(kPassClips[0]);

/// Per-instance state; render calls of one instance are serialised by `mutex`, so the effect is
/// declared fully thread-safe (different instances and frames may render at the same time).
struct Instance {
    bool general = false;
    OfxImageClipHandle source = nullptr;
    OfxImageClipHandle output = nullptr;
    OfxImageClipHandle aux[kNumAux] = {};
    OfxImageClipHandle pass[kNumPass] = {};
    std::mutex mutex;
    SequenceRunner runner;
};

Instance& instanceOf(OfxImageEffectHandle effect)
{
    OfxPropertySetHandle props = nullptr;
    check(suites().effect->getPropertySet(effect, &props), "getting the instance properties");
    auto* inst = static_cast<Instance*>(Props(props).getPointer(kOfxPropInstanceData));
    if (!inst)
        throw OfxError(kOfxStatErrBadHandle, "instance has no data");
    return *inst;
}

Props effectProps(OfxImageEffectHandle effect)
{
    OfxPropertySetHandle props = nullptr;
    check(suites().effect->getPropertySet(effect, &props), "getting the effect properties");
    return Props(props);
}

bool connected(OfxImageClipHandle clip)
{
    if (!clip)
        return false;
    OfxPropertySetHandle props = nullptr;
    check(suites().effect->clipGetPropertySet(clip, &props), "getting clip properties");
    return Props(props).getInt(kOfxImageClipPropConnected) != 0;
}

OfxRectD sourceRod(const Instance& inst, double time)
{
    OfxRectD rod {};
    check(suites().effect->clipGetRegionOfDefinition(inst.source, time, &rod),
        "getting the Source region of definition");
    return rod;
}

void describe(OfxImageEffectHandle effect)
{
    Props p = effectProps(effect);
    p.set(kOfxPropLabel, "afn Denoise");
    // Hosts file it under their filter menu (Nuke, Natron: Filter > Denoise > afn Denoise).
    p.set(kOfxImageEffectPluginPropGrouping, "Filter/Denoise");
    p.set(kOfxPropPluginDescription,
        "Monte Carlo render denoiser (afn library): spatial and temporal methods over a noisy "
        "beauty with optional albedo, normal, depth and motion inputs.");
    p.setStrings(kOfxImageEffectPropSupportedContexts,
        { kOfxImageEffectContextGeneral, kOfxImageEffectContextFilter });
    p.set(kOfxImageEffectPropSupportedPixelDepths, kOfxBitDepthFloat);
    p.set(kOfxImageEffectPropSupportsTiles, 1);
    p.set(kOfxImageEffectPropSupportsMultiResolution, 1);
    p.set(kOfxImageEffectPropTemporalClipAccess, 1);
    p.set(kOfxImageEffectPropSupportsMultipleClipDepths, 0);
    p.set(kOfxImageEffectPluginRenderThreadSafety, kOfxImageEffectRenderFullySafe);
    p.set(kOfxImageEffectPluginPropHostFrameThreading, 0); // the library threads each frame
    // 2 = "prefers sequential": in-order renders continue the history (see sequence_runner.h).
    p.trySet(kOfxImageEffectInstancePropSequentialRender, 2);
    // Icon (SVG, PNG) relative to Contents/Resources; hosts also look for <identifier>.png there.
    try {
        p.setStrings(kOfxPropIcon, { "", std::string(kDenoiseIdentifier) + ".png" });
    } catch (const OfxError&) {
        // a host without icon support: nothing to do
    }
}

void defineClip(OfxImageEffectHandle effect, const char* name, bool optional, bool alpha)
{
    OfxPropertySetHandle props = nullptr;
    check(suites().effect->clipDefine(effect, name, &props), std::string("defining clip ") + name);
    Props p(props);
    std::vector<std::string> comps = { kOfxImageComponentRGBA, kOfxImageComponentRGB };
    if (alpha)
        comps.push_back(kOfxImageComponentAlpha);
    p.setStrings(kOfxImageEffectPropSupportedComponents, comps);
    p.set(kOfxImageEffectPropTemporalClipAccess, 1);
    p.set(kOfxImageEffectPropSupportsTiles, 1);
    if (optional)
        p.set(kOfxImageClipPropOptional, 1);
}

void describeInContext(OfxImageEffectHandle effect, OfxPropertySetHandle inArgs)
{
    const std::string context = Props(inArgs).getString(kOfxImageEffectPropContext);
    const bool general = context == kOfxImageEffectContextGeneral;
    if (!general && context != kOfxImageEffectContextFilter)
        throw OfxError(kOfxStatErrUnsupported, "context " + context + " is not supported");
    defineClip(effect, kOfxImageEffectOutputClipName, false, false);
    defineClip(effect, kOfxImageEffectSimpleSourceClipName, false, false);
    if (general) {
        for (const ClipRole& c : kAuxClips)
            defineClip(effect, c.clip, true,
                std::string(c.role) == AFN_IMAGE_DEPTH || std::string(c.role) == AFN_IMAGE_MASK);
        for (const ClipRole& c : kPassClips)
            defineClip(effect, c.clip, true, false);
    }
    // The Filter context has only Source: frames are denoised on their own unless asked, and the
    // parameters that need auxiliary inputs are hidden.
    defineParams(effect, general);
}

void createInstance(OfxImageEffectHandle effect)
{
    Props p = effectProps(effect);
    auto inst = std::make_unique<Instance>();
    inst->general = p.getString(kOfxImageEffectPropContext) == kOfxImageEffectContextGeneral;
    auto clip = [&](const char* name) {
        OfxImageClipHandle h = nullptr;
        check(suites().effect->clipGetHandle(effect, name, &h, nullptr),
            std::string("getting clip ") + name);
        return h;
    };
    inst->source = clip(kOfxImageEffectSimpleSourceClipName);
    inst->output = clip(kOfxImageEffectOutputClipName);
    if (inst->general) {
        for (int i = 0; i < kNumAux; ++i)
            inst->aux[i] = clip(kAuxClips[i].clip);
        for (int i = 0; i < kNumPass; ++i)
            inst->pass[i] = clip(kPassClips[i].clip);
    }
    const bool general = inst->general;
    p.setPointer(kOfxPropInstanceData, inst.release());
    updateParamStates(effect, general);
}

void destroyInstance(OfxImageEffectHandle effect)
{
    Instance* inst = &instanceOf(effect);
    effectProps(effect).setPointer(kOfxPropInstanceData, nullptr);
    delete inst;
}

/// First frame the history may use: the Source clip's first frame, or the start frame when it is
/// switched on and later.
double historyStart(const Instance& inst, const Settings& s)
{
    OfxPropertySetHandle props = nullptr;
    check(suites().effect->clipGetPropertySet(inst.source, &props), "getting Source properties");
    const double first = Props(props).getDouble(kOfxImageEffectPropFrameRange, 0);
    return s.useStartFrame ? std::max(first, double(s.startFrame)) : first;
}

/// Input clips that take part (Source plus the connected optional clips; the pass clips when the
/// Output is the pass), with their names. OfxError when the Output is the pass and the Pass clip
/// is not connected.
std::vector<std::pair<const char*, InputClip>> inputClips(
    const Instance& inst, const Settings& settings)
{
    std::vector<std::pair<const char*, InputClip>> out;
    out.push_back({ kOfxImageEffectSimpleSourceClipName, { AFN_IMAGE_COLOR, inst.source } });
    for (int i = 0; i < kNumAux; ++i)
        if (connected(inst.aux[i]))
            out.push_back({ kAuxClips[i].clip, { kAuxClips[i].role, inst.aux[i] } });
    if (settings.outputPass) {
        if (!connected(inst.pass[0]))
            throw OfxError(kOfxStatFailed,
                "Output is set to Pass, but the Pass clip is not connected (connect a light-path "
                "pass, or set Output to Beauty)");
        for (int i = 0; i < kNumPass; ++i)
            if (connected(inst.pass[i]))
                out.push_back({ kPassClips[i].clip, { kPassClips[i].role, inst.pass[i] } });
    }
    return out;
}

OfxStatus regionsOfInterest(
    OfxImageEffectHandle effect, OfxPropertySetHandle inArgs, OfxPropertySetHandle outArgs)
{
    Instance& inst = instanceOf(effect);
    const Settings settings = readSettings(effect);
    if (settings.method == "identity")
        return kOfxStatReplyDefault;
    // Every method works on whole frames (temporal history, global regressions, wide kernels):
    // ask for the full Source frame whatever the tile.
    const OfxRectD rod = sourceRod(inst, Props(inArgs).getDouble(kOfxPropTime));
    Props out(outArgs);
    for (const auto& [name, in] : inputClips(inst, settings))
        out.setDoubles(
            (std::string(kOfxImageClipPropRoI) + name).c_str(), { rod.x1, rod.y1, rod.x2, rod.y2 });
    return kOfxStatOK;
}

OfxStatus framesNeeded(
    OfxImageEffectHandle effect, OfxPropertySetHandle inArgs, OfxPropertySetHandle outArgs)
{
    Instance& inst = instanceOf(effect);
    const double t = Props(inArgs).getDouble(kOfxPropTime);
    const Settings s = readSettings(effect);
    const double first = s.method != "identity" ? t - replayFrames(t, s, historyStart(inst, s)) : t;
    Props out(outArgs);
    for (const auto& [name, in] : inputClips(inst, s))
        out.setDoubles((std::string(kOfxImageClipPropFrameRange) + name).c_str(), { first, t });
    return kOfxStatOK;
}

OfxStatus render(OfxImageEffectHandle effect, OfxPropertySetHandle inArgs)
{
    Instance& inst = instanceOf(effect);
    Props args(inArgs);
    const double time = args.getDouble(kOfxPropTime);
    const OfxRectI renderWindow = { args.getInt(kOfxImageEffectPropRenderWindow, 0),
        args.getInt(kOfxImageEffectPropRenderWindow, 1),
        args.getInt(kOfxImageEffectPropRenderWindow, 2),
        args.getInt(kOfxImageEffectPropRenderWindow, 3) };
    const double sx = args.getDouble(kOfxImageEffectPropRenderScale, 0);
    const double sy = args.getDouble(kOfxImageEffectPropRenderScale, 1);

    FrameRequest req;
    req.instance = effect;
    req.windowCanonical = sourceRod(inst, time);
    // Pixel aspect ratio 1 is assumed (render-denoising inputs are square-pixel renders).
    const OfxRectD& c = req.windowCanonical;
    req.window = { int(std::floor(c.x1 * sx + 1e-6)), int(std::floor(c.y1 * sy + 1e-6)),
        int(std::ceil(c.x2 * sx - 1e-6)), int(std::ceil(c.y2 * sy - 1e-6)) };
    if (req.window.x2 <= req.window.x1 || req.window.y2 <= req.window.y1)
        throw OfxError(kOfxStatFailed, "the Source clip has an empty region of definition");
    req.renderScale = sx;
    const Settings settings = readSettings(effect);
    for (const auto& [name, in] : inputClips(inst, settings))
        req.inputs.push_back(in);
    req.historyStart = historyStart(inst, settings);

    ClipImage out(inst.output, time);
    if (!out.valid())
        throw OfxError(kOfxStatFailed, "the host gave no Output image");
    // mix < 1: the tile of Source (of Pass, when that is the output) at this time, blended in
    // after denoising (the cached denoised frames do not depend on the mix, so changing or
    // animating it never replays the history).
    const float mix = static_cast<float>(readMix(effect, time));
    std::unique_ptr<ClipImage> source;
    if (mix < 1.0f) {
        const OfxRectD tile = { renderWindow.x1 / sx, renderWindow.y1 / sy, renderWindow.x2 / sx,
            renderWindow.y2 / sy };
        source = std::make_unique<ClipImage>(
            settings.outputPass ? inst.pass[0] : inst.source, time, &tile);
        if (!source->valid())
            throw OfxError(kOfxStatFailed, "no Source image at time " + std::to_string(time));
    }
    std::lock_guard<std::mutex> lock(inst.mutex);
    const std::vector<float>& frame = inst.runner.frame(time, settings, req);
    writeTile(out, renderWindow, frame.data(), req.window, source.get(), mix);
    return kOfxStatOK;
}

} // namespace

OfxStatus denoiseAction(const std::string& action, OfxImageEffectHandle effect,
    OfxPropertySetHandle inArgs, OfxPropertySetHandle outArgs)
{
    if (action == kOfxActionLoad)
        return fetchSuites() ? kOfxStatOK : kOfxStatErrMissingHostFeature;
    if (action == kOfxActionUnload)
        return kOfxStatOK;
    if (action == kOfxActionDescribe) {
        describe(effect);
        return kOfxStatOK;
    }
    if (action == kOfxImageEffectActionDescribeInContext) {
        describeInContext(effect, inArgs);
        return kOfxStatOK;
    }
    if (action == kOfxActionCreateInstance) {
        createInstance(effect);
        return kOfxStatOK;
    }
    if (action == kOfxActionDestroyInstance) {
        destroyInstance(effect);
        return kOfxStatOK;
    }
    if (action == kOfxActionPurgeCaches) {
        Instance& inst = instanceOf(effect);
        std::lock_guard<std::mutex> lock(inst.mutex);
        inst.runner.clear();
        return kOfxStatOK;
    }
    if (action == kOfxActionInstanceChanged) {
        Props in(inArgs);
        if (in.getString(kOfxPropType) == kOfxTypeParameter
            && affectsParamStates(in.getString(kOfxPropName)))
            updateParamStates(effect, instanceOf(effect).general);
        return kOfxStatOK;
    }
    if (action == kOfxImageEffectActionGetRegionOfDefinition) {
        const OfxRectD rod = sourceRod(instanceOf(effect), Props(inArgs).getDouble(kOfxPropTime));
        Props(outArgs).setDoubles(
            kOfxImageEffectPropRegionOfDefinition, { rod.x1, rod.y1, rod.x2, rod.y2 });
        return kOfxStatOK;
    }
    if (action == kOfxImageEffectActionGetRegionsOfInterest)
        return regionsOfInterest(effect, inArgs, outArgs);
    if (action == kOfxImageEffectActionGetFramesNeeded)
        return framesNeeded(effect, inArgs, outArgs);
    if (action == kOfxImageEffectActionIsIdentity) {
        // The identity method, or a mix of 0: the host passes Source (or Pass, when that is the
        // output) through.
        const double time = Props(inArgs).getDouble(kOfxPropTime);
        const Settings settings = readSettings(effect);
        if (settings.method != "identity" && readMix(effect, time) > 0.0)
            return kOfxStatReplyDefault;
        Props out(outArgs);
        out.set(kOfxPropName,
            settings.outputPass ? kPassClips[0].clip : kOfxImageEffectSimpleSourceClipName);
        out.set(kOfxPropTime, time);
        return kOfxStatOK;
    }
    if (action == kOfxImageEffectActionRender) {
        try {
            return render(effect, inArgs);
        } catch (const Aborted&) {
            return kOfxStatFailed; // the host asked to stop; nothing was written
        }
    }
    return kOfxStatReplyDefault;
}

} // namespace afnofx
