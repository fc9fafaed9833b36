// SPDX-License-Identifier: Apache-2.0
#include "filter/filter.h"

#include "base/exception.h"
#include "base/parallel.h"
#include "filter/pass_images.h"
#include "filter/registry.h"
#include "filter/work_mask.h"
#include "stages/demodulate.h"

#include <algorithm>
#include <sstream>

namespace afn {

const std::vector<std::string>& inputImageNames()
{
    static const std::vector<std::string> names
        = { AFN_IMAGE_COLOR, AFN_IMAGE_ALBEDO, AFN_IMAGE_NORMAL, AFN_IMAGE_DEPTH,
              AFN_IMAGE_POSITION, AFN_IMAGE_MOTION, AFN_IMAGE_ALPHA, AFN_IMAGE_MASK };
    return names;
}

static bool isInputName(const std::string& n)
{
    const auto& v = inputImageNames();
    return std::find(v.begin(), v.end(), n) != v.end();
}

static std::string sizeText(int w, int h)
{
    return std::to_string(w) + "x" + std::to_string(h);
}

Filter::Filter(const FilterType& type)
    : m_type(type)
    , m_params(&type.params)
    , m_stages(type.stages)
{
}

Filter::Filter(const FilterType& type, StageNeeds stages)
    : m_type(type)
    , m_params(&type.params)
    , m_stages(stages)
{
}

namespace {

/// The feature of `type` that image name `name` ("feature.<x>") binds, or null.
const FeatureOutput* featureOf(const FilterType& type, const std::string& name)
{
    const std::string prefix = AFN_IMAGE_FEATURE_PREFIX;
    if (name.compare(0, prefix.size(), prefix) != 0)
        return nullptr;
    for (const FeatureOutput& f : type.features)
        if (name.compare(prefix.size(), std::string::npos, f.name) == 0)
            return &f;
    return nullptr;
}

} // namespace

bool Filter::outputBound() const
{
    return m_images.count(AFN_IMAGE_OUTPUT) != 0;
}

bool Filter::anyFeatureBound() const
{
    for (const FeatureOutput& f : m_type.features)
        if (m_images.count(AFN_IMAGE_FEATURE_PREFIX + f.name) != 0)
            return true;
    return false;
}

void Filter::writeFeature(const std::string& name, const Image& image) const
{
    auto it = m_images.find(AFN_IMAGE_FEATURE_PREFIX + name);
    if (it == m_images.end())
        return;
    const FeatureOutput* f = featureOf(m_type, it->first);
    if (!f || image.channels() < f->channels || image.width() != m_frame.width
        || image.height() != m_frame.height)
        throwInvalidOperation("feature '" + name + "' does not match its description");
    const ImageView dst = it->second.view();
    parallelRows(dst.height, [&](int y0, int y1) {
        for (int y = y0; y < y1; ++y)
            for (int x = 0; x < dst.width; ++x) {
                const float* v = image.at(x, y);
                float* o = dst.atMutable(x, y);
                for (int c = 0; c < f->channels; ++c)
                    o[c] = v[c];
            }
    });
}

ImageView ImageBinding::view() const
{
    ImageView v;
    v.base = static_cast<const std::byte*>(ptr) + byteOffset;
    v.width = width;
    v.height = height;
    v.channels = channels();
    v.pixelStride = pixelStride;
    v.rowStride = rowStride;
    return v;
}

void Filter::setImage(const std::string& name, const ImageBinding& b)
{
    const FeatureOutput* feature = featureOf(m_type, name);
    if (name != AFN_IMAGE_OUTPUT && !isInputName(name) && !feature && !isPassImageName(name)) {
        std::string features;
        for (const FeatureOutput& f : m_type.features)
            features += (features.empty() ? "" : ", ") + (AFN_IMAGE_FEATURE_PREFIX + f.name);
        throwInvalidArgument("unknown image '" + name
            + "' (inputs: color, albedo, normal, depth, position, motion, alpha, mask, "
              "pass.<name>, passFactor.<name>; outputs: output, passOutput.<name>"
            + (features.empty() ? "" : "; features of " + m_type.name + ": " + features) + ")");
    }
    if (b.ptr == nullptr)
        throwInvalidArgument("image '" + name + "': null pointer");
    if (b.format < AFN_FORMAT_FLOAT || b.format > AFN_FORMAT_FLOAT4)
        throwInvalidArgument(
            "image '" + name + "': unsupported format " + std::to_string(b.format));
    if (b.width <= 0 || b.height <= 0)
        throwInvalidArgument("image '" + name + "': zero size " + sizeText(b.width, b.height));
    if (std::abs(b.pixelStride) < static_cast<std::ptrdiff_t>(b.channels() * sizeof(float)))
        throwInvalidArgument("image '" + name + "': pixel stride smaller than a pixel");
    m_images[name] = b;
    m_committed = false;
}

void Filter::unsetImage(const std::string& name)
{
    m_images.erase(name);
    m_committed = false;
}

void Filter::setFloats(const std::string& name, const std::vector<float>& values)
{
    if (name == AFN_ARRAY_VIEW_PROJECTION) {
        if (values.size() != 16)
            throwInvalidArgument("viewProjection needs 16 floats");
        std::copy(values.begin(), values.end(), m_camera.viewProjection.begin());
        m_camera.valid = true;
    } else if (name == AFN_ARRAY_PIXEL_OFFSET) {
        if (values.size() != 2)
            throwInvalidArgument("pixelOffset needs 2 floats");
        m_camera.pixelOffset = { values[0], values[1] };
    } else {
        throwInvalidArgument("unknown array parameter '" + name + "'");
    }
}

void Filter::setData(const std::string& name, const void*, std::size_t)
{
    throwInvalidArgument("this filter takes no data parameter '" + name + "'");
}

void Filter::validateBindings() const
{
    auto color = m_images.find(AFN_IMAGE_COLOR);
    if (color == m_images.end())
        throwInvalidOperation("no 'color' image set");
    const int w = color->second.width, h = color->second.height;
    for (const auto& [name, b] : m_images) {
        if (b.width != w || b.height != h)
            throwInvalidArgument(name + " size " + sizeText(b.width, b.height)
                + " does not match color " + sizeText(w, h));
    }
    auto need = [&](const char* n, int minCh) {
        auto it = m_images.find(n);
        if (it != m_images.end() && it->second.channels() < minCh)
            throwInvalidArgument(std::string("image '") + n + "' needs at least "
                + std::to_string(minCh) + " channels");
    };
    need(AFN_IMAGE_COLOR, 3);
    need(AFN_IMAGE_ALBEDO, 3);
    need(AFN_IMAGE_NORMAL, 3);
    need(AFN_IMAGE_POSITION, 3);
    need(AFN_IMAGE_MOTION, 2);
    need(AFN_IMAGE_OUTPUT, 3);
    for (const FeatureOutput& f : m_type.features)
        need((AFN_IMAGE_FEATURE_PREFIX + f.name).c_str(), f.channels);
    validatePassImages(m_images, outputBound());
    if (!outputBound() && !anyFeatureBound())
        throwInvalidOperation("no 'output' image set");
}

void Filter::runPassTransfer()
{
    const std::vector<PassBinding> passes = passBindingsOf(m_images);
    if (passes.empty())
        return;
    PassGuides g;
    g.beauty = m_images.at(AFN_IMAGE_COLOR).view();
    g.denoised = m_images.at(AFN_IMAGE_OUTPUT).view();
    if (auto n = m_images.find(AFN_IMAGE_NORMAL); n != m_images.end())
        g.normal = n->second.view();
    if (auto d = m_images.find(AFN_IMAGE_DEPTH); d != m_images.end())
        g.depth = d->second.view();
    if (m_stages.reproject != StageNeeds::Reproject::None)
        g.reprojector = &m_reprojector;
    g.trust = historyTrust();
    m_passTransfer.run(g, passes);
}

void Filter::commit()
{
    validateBindings();
    m_conventions = conventionsBinding().read(m_params);
    m_work = workBinding().read(m_params);
    if (m_stages.demodulate)
        m_aux.setSettings(auxBinding().read(m_params));
    if (m_stages.reproject != StageNeeds::Reproject::None) {
        ReprojectSettings r = reprojectBinding().read(m_params);
        r.boxFallback = m_stages.reproject == StageNeeds::Reproject::BilinearWithBoxFallback;
        m_reprojector.setSettings(r);
    }
    if (m_stages.accumulate) {
        m_accumulator.setSettings(accumulationBinding().read(m_params));
        m_accumulator.setTrustSettings(historyTrustBinding().read(m_params));
    }
    configure();
    // The type's stages, not this filter's: a device filter runs them itself but restores here.
    m_restoreOn = false;
    if (m_type.stages.demodulate) {
        m_restoreSettings = restoreBinding().read(m_params);
        m_restoreOn
            = restoreOn(m_restoreSettings, auxBinding().read(m_params).spp, samplesMadeFor());
    }
    m_committed = true;
}

void Filter::reset()
{
    m_frameIndex = 0;
    m_prevCamera = Camera {};
    m_prevInputs.clear();
}

void Filter::runStages()
{
    if (m_frame.frameIndex == 0) {
        m_reprojector.reset();
        m_accumulator.reset();
        m_aux.reset();
        resetHistory();
        m_passTransfer.reset();
    }
    const bool reproject = m_stages.reproject != StageNeeds::Reproject::None;
    if (m_stages.demodulate)
        m_aux.prepare(m_frame); // may rewrite the normal and depth (noisy mode)
    if (reproject)
        m_reprojector.compute(m_frame);
    if (m_stages.demodulate)
        m_aux.finish(m_frame, reproject ? &m_reprojector : nullptr); // may rewrite the albedo
    if (m_stages.demodulate && m_stages.accumulate) {
        // Demodulation (in place: the radiance is not read again), accumulation and, for ta, the
        // remodulated output run per band of rows in one pass: a band's rows are still in cache
        // for the next step (the values are those of three separate passes).
        // The history trust (stages/history_trust.h) needs every block's statistics before the
        // blend: two passes, demodulation with the history's gather, then blend and output.
        const bool writeOutput = outputWrittenByStages();
        m_accumulator.begin(m_reprojector, m_frame.width, m_frame.height);
        parallelRows(m_frame.height, [&](int y0, int y1) {
            demodulateRows(m_frame, m_frame.color, y0, y1);
            m_accumulator.gatherRows(m_reprojector, m_frame.color, y0, y1);
        });
        m_accumulator.finishTrust();
        parallelRows(m_frame.height, [&](int y0, int y1) {
            m_accumulator.blendRows(m_reprojector, m_frame.color, y0, y1);
            if (writeOutput)
                writeRemodulatedRows(m_accumulator.color(), y0, y1);
        });
        m_accumulator.end();
    } else if (m_stages.demodulate) {
        demodulate(m_frame, m_frame.color);
    } else if (m_stages.accumulate) {
        m_accumulator.accumulate(m_reprojector, m_frame.color);
    }
}

const AuxReport& Filter::auxReport() const
{
    if (m_aux.sharesPending()) {
        // The last frame's inputs as given (a clean history rewrites none): the albedo is still
        // the frame's; its normal and depth became the reprojection's history (takeGeometry).
        const bool kept = m_stages.reproject != StageNeeds::Reproject::None;
        const Image& normal = kept ? m_reprojector.previousNormal() : m_frame.normal;
        const Image& depth = kept ? m_reprojector.previousDepth() : m_frame.depth;
        m_aux.measureShares(m_frame.albedo.view(), normal.view(), depth.view());
    }
    return m_aux.report();
}

void Filter::reportProgress(double fraction) const
{
    if (m_progress && !m_progress(std::clamp(fraction, 0.0, 1.0)))
        throw Exception(AFN_ERROR_CANCELLED, "execution cancelled by the progress callback");
}

void Filter::execute()
{
    if (!m_committed)
        throwInvalidOperation("filter has uncommitted changes; call commit first");
    const ImageBinding& color = m_images.at(AFN_IMAGE_COLOR);
    std::string inputs;
    for (const auto& [name, b] : m_images)
        if (isInputName(name))
            inputs += name + ":" + std::to_string(b.channels()) + " ";
    if (m_frameIndex > 0) {
        if (color.width != m_prevWidth || color.height != m_prevHeight)
            throwInvalidArgument("frame size " + sizeText(color.width, color.height)
                + " differs from the previous frame's " + sizeText(m_prevWidth, m_prevHeight)
                + " (reset the filter at a cut)");
        if (inputs != m_prevInputs)
            throwInvalidArgument("frame inputs (" + inputs + ") differ from the previous frame's ("
                + m_prevInputs + ")");
    }
    reportProgress(0.0);
    m_stats = InputStats {};
    gatherFrame(m_images, m_conventions, m_frame, m_stats);
    m_skipped = buildWorkMask(m_images, m_work, m_frame);
    m_frame.camera = m_camera;
    m_frame.prevCamera = m_frameIndex > 0 ? m_prevCamera : Camera {};
    m_frame.frameIndex = m_frameIndex;
    m_missingInputs = missingInputs(m_type, m_frame);
    const bool restore = m_restoreOn && outputBound();
    if (restore && m_stages.demodulate)
        m_noisy = m_frame.color; // the stages demodulate the frame's colour in place
    m_restoreRan = false;
    runStages();
    {
        // The frame's geometry becomes the reprojection's history once the method has run (also
        // when it throws: the stages' history has advanced with this frame): swapped, not
        // copied; the next gather rewrites the buffers the frame gets back.
        struct KeepGeometry {
            Filter& self;
            ~KeepGeometry()
            {
                if (self.m_stages.reproject != StageNeeds::Reproject::None)
                    self.m_reprojector.takeGeometry(self.m_frame);
            }
        } keep { *this };
        const bool written = outputWrittenByStages();
        const bool pending = outputBound() && !written;
        const Image* irr = pending ? denoiseDemodulated(m_frame) : nullptr;
        const Image* rad = pending && !irr ? denoiseRadiance(m_frame) : nullptr;
        if (irr) {
            writeRemodulated(*irr);
        } else if (rad) {
            writeOutput(*rad);
        } else if (!written) {
            m_output.resize(m_frame.width, m_frame.height, 3);
            denoise(m_frame, m_output);
            if (outputBound())
                writeOutput(m_output);
        }
    }
    if (restore) {
        m_restore.run(m_stages.demodulate ? m_noisy : m_frame.color, m_frame,
            m_restoreSettings.noise, m_images.at(AFN_IMAGE_OUTPUT).view());
        m_restoreRan = true;
    }
    if (outputBound())
        runPassTransfer();
    writeTrustFeature();
    reportProgress(1.0);
    m_prevWidth = color.width;
    m_prevHeight = color.height;
    m_prevInputs = inputs;
    m_prevCamera = m_camera;
    ++m_frameIndex;
}

void Filter::writeTrustFeature()
{
    if (m_images.count(std::string(AFN_IMAGE_FEATURE_PREFIX) + kHistoryTrustFeature) == 0)
        return;
    if (const HistoryTrust* t = historyTrust()) {
        t->map(m_trustMap);
    } else { // no trust measured: every history kept
        m_trustMap.resize(m_frame.width, m_frame.height, 1);
        for (int y = 0; y < m_frame.height; ++y)
            std::fill(m_trustMap.at(0, y), m_trustMap.at(0, y) + m_frame.width, 1.0f);
    }
    writeFeature(kHistoryTrustFeature, m_trustMap);
}

void Filter::writeOutput(const Image& radiance) const
{
    const ImageBinding& out = m_images.at(AFN_IMAGE_OUTPUT);
    const ImageView dst = out.view();
    const bool hasAlpha = !m_frame.alpha.empty();
    parallelRows(dst.height, [&](int y0, int y1) {
        for (int y = y0; y < y1; ++y)
            for (int x = 0; x < dst.width; ++x) {
                float* o = dst.atMutable(x, y);
                const float* r = radiance.at(x, y);
                o[0] = r[0];
                o[1] = r[1];
                o[2] = r[2];
                if (dst.channels == 4)
                    o[3] = hasAlpha ? m_frame.alpha(x, y, 0) : 1.0f;
            }
    });
}

bool Filter::outputWrittenByStages() const
{
    return m_stages.demodulate && m_stages.accumulate && outputIsAccumulation() && outputBound();
}

void Filter::writeRemodulated(const Image& irradiance) const
{
    parallelRows(m_frame.height, [&](int y0, int y1) { writeRemodulatedRows(irradiance, y0, y1); });
}

void Filter::writeRemodulatedRows(const Image& irradiance, int y0, int y1) const
{
    const ImageBinding& out = m_images.at(AFN_IMAGE_OUTPUT);
    const ImageView dst = out.view();
    const bool hasAlpha = !m_frame.alpha.empty();
    for (int y = y0; y < y1; ++y) {
        remodulateRow(m_frame, irradiance, y, reinterpret_cast<std::byte*>(dst.atMutable(0, y)),
            dst.pixelStride, true);
        if (dst.channels == 4)
            for (int x = 0; x < dst.width; ++x)
                dst.atMutable(x, y)[3] = hasAlpha ? m_frame.alpha(x, y, 0) : 1.0f;
    }
}

} // namespace afn
