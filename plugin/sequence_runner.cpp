// SPDX-License-Identifier: Apache-2.0
#include "sequence_runner.h"

#include "clip_image.h"
#include "ofx_support.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <iterator>
#include <memory>
#include <sstream>

namespace afnofx {

namespace {

constexpr size_t kCachedFrames = 4;

bool methodHasParam(const std::string& method, const char* name)
{
    AFNParamInfo info {};
    for (int i = 0; afnGetFilterTypeParam(method.c_str(), i, &info); ++i)
        if (std::strcmp(info.name, name) == 0)
            return true;
    return false;
}

bool abortRequested(void* instance, double)
{
    return suites().effect->abort(static_cast<OfxImageEffectHandle>(instance)) == 0;
}

std::string stateKey(const Settings& s, const FrameRequest& r)
{
    std::ostringstream os;
    os.precision(17);
    os << s.key() << '|' << r.window.x1 << ',' << r.window.y1 << ',' << r.window.x2 << ','
       << r.window.y2 << '|' << r.renderScale << '|' << r.historyStart << '|';
    for (const InputClip& c : r.inputs)
        os << c.role << ',';
    return os.str();
}

} // namespace

int replayFrames(double time, const Settings& settings, double historyStart)
{
    if (!settings.temporal || time < historyStart)
        return 0;
    const double available = std::floor(time - historyStart + 1e-9);
    return static_cast<int>(std::min<double>(settings.historyFrames, available));
}

void SequenceRunner::clear()
{
    m_results.clear();
    m_hasState = false;
}

void SequenceRunner::checkError(const char* what)
{
    std::string msg;
    const afn::Error e = m_device.getError(&msg);
    if (e == afn::Error::Cancelled)
        throw Aborted {};
    if (e != afn::Error::None)
        throw OfxError(kOfxStatFailed, std::string(what) + ": " + msg);
}

std::vector<float>& SequenceRunner::storeSlot(const std::string& key, double time)
{
    for (auto it = m_results.begin(); it != m_results.end(); ++it)
        if (it->key == key && it->time == time) {
            m_results.erase(it);
            break;
        }
    Result r;
    if (m_results.size() >= kCachedFrames) {
        r.rgba = std::move(m_results.front().rgba); // reuse the oldest frame's memory
        m_results.pop_front();
    }
    r.key = key;
    r.time = time;
    m_results.push_back(std::move(r));
    return m_results.back().rgba;
}

const std::vector<float>& SequenceRunner::frame(
    double time, const Settings& settings, const FrameRequest& req)
{
    const std::string key = stateKey(settings, req);
    for (const Result& r : m_results)
        if (r.key == key && r.time == time)
            return r.rgba;

    const std::string weights = settings.weightsPath + "|" + settings.weightsStamp;
    if (!m_filter || m_filterMethod != settings.method || m_filterWeights != weights
        || m_deviceChoice != settings.device) {
        createFilter(settings, req.instance);
        m_filterMethod = settings.method;
        m_filterWeights.clear();
        m_hasState = false;
        loadWeights(settings);
        m_filterWeights = weights;
    }
    m_filter.setProgressMonitorFunction(abortRequested, req.instance);

    // Frames to run: only t without history; t alone when the filter stands at t-1 with the same
    // key and t-1 may be used as history (frames rendered in order keep their whole history);
    // otherwise at most historyFrames earlier frames, not before historyStart (the host may have
    // scrubbed or changed a parameter). Times step by whole frames back from t.
    const bool continues = settings.temporal && m_hasState && m_stateKey == key
        && m_stateTime == time - 1.0 && time - 1.0 >= req.historyStart;
    const int backSteps = continues ? 0 : replayFrames(time, settings, req.historyStart);
    if (!continues)
        m_filter.reset();
    m_hasState = false;
    for (int n = backSteps; n >= 0; --n) {
        const double t = time - n;
        if (n > 0 && suites().effect->abort(req.instance))
            throw Aborted {};
        std::vector<float>& out = storeSlot(key, t);
        try {
            runFrame(t, settings, req, out);
        } catch (...) {
            m_results.pop_back(); // never keep a half-written frame
            throw;
        }
        m_stateKey = key;
        m_stateTime = t;
        m_hasState = settings.temporal;
    }
    return m_results.back().rgba;
}

void SequenceRunner::createFilter(const Settings& settings, OfxImageEffectHandle instance)
{
    m_filter = afn::FilterRef();
    m_hasState = false;
    m_deviceChoice = settings.device;
    std::string why;
    if (settings.device != "cpu") {
        if (openOnCuda(settings, why))
            return;
        postNote(instance, "afn: device auto: " + why + "; denoising on the CPU");
    }
    if (!m_device || m_device.get("type") != AFN_DEVICE_TYPE_CPU) {
        m_device = afn::newDevice(afn::DeviceType::CPU);
        m_device.commit();
        checkError("creating the afn device");
    }
    m_filter = m_device.newFilter(settings.method.c_str());
    checkError(("creating filter " + settings.method).c_str());
}

bool SequenceRunner::openOnCuda(const Settings& settings, std::string& why)
{
    const bool onCuda = m_device && m_device.get("type") == AFN_DEVICE_TYPE_CUDA;
    afn::DeviceRef cuda = onCuda ? m_device : afn::newDevice(afn::DeviceType::CUDA);
    if (!cuda) {
        const char* reason = nullptr;
        afnGetDeviceError(nullptr, &reason);
        why = std::string("no CUDA device (") + (reason ? reason : "unknown reason") + ")";
        if (settings.device == "cuda")
            throw OfxError(kOfxStatFailed, "device cuda: " + why);
        return false;
    }
    if (!onCuda)
        cuda.commit();
    afn::FilterRef filter = cuda.newFilter(settings.method.c_str());
    std::string message;
    const afn::Error error = cuda.getError(&message);
    if (error == afn::Error::None) {
        m_device = cuda;
        m_filter = filter;
        return true;
    }
    if (settings.device == "cuda" || error != afn::Error::Unsupported)
        throw OfxError(kOfxStatFailed, "creating filter " + settings.method + ": " + message);
    why = "method '" + settings.method + "' runs on the CPU only";
    return false;
}

void SequenceRunner::loadWeights(const Settings& settings)
{
    if (settings.weightsPath.empty())
        return;
    std::vector<char> bytes;
    if (!afn::readFile(settings.weightsPath, bytes))
        throw OfxError(
            kOfxStatFailed, "cannot read the weights file '" + settings.weightsPath + "'");
    m_filter.setData(AFN_DATA_WEIGHTS, bytes.data(), bytes.size());
    checkError(("weights file '" + settings.weightsPath + "'").c_str());
}

void SequenceRunner::runFrame(
    double time, const Settings& settings, const FrameRequest& req, std::vector<float>& out)
{
    const int w = req.window.x2 - req.window.x1, h = req.window.y2 - req.window.y1;
    AFNFilter f = m_filter.getHandle();
    // Images stay fetched until the filter has executed.
    std::vector<std::unique_ptr<ClipImage>> images;
    m_scratch.resize(req.inputs.size());
    for (size_t i = 0; i < req.inputs.size(); ++i) {
        const InputClip& in = req.inputs[i];
        images.emplace_back(new ClipImage(in.clip, time, &req.windowCanonical));
        const ClipImage& img = *images.back();
        std::ostringstream where;
        where << "clip for '" << in.role << "' at time " << time;
        if (!img.valid())
            throw OfxError(kOfxStatFailed, "no image from the " + where.str());
        const StridedView v = viewWindow(img, req.window, m_scratch[i]);
        const std::string role = in.role;
        int need = role == AFN_IMAGE_DEPTH || role == AFN_IMAGE_MASK ? 1
            : role == AFN_IMAGE_MOTION                               ? 2
                                                                     : 3;
        if (v.components < need)
            throw OfxError(kOfxStatErrImageFormat,
                "the " + where.str() + " has " + std::to_string(v.components)
                    + " components, needs " + std::to_string(need));
        afnSetFilterImage(
            f, in.role, v.ptr, static_cast<AFNFormat>(need), w, h, 0, v.pixelStride, v.rowStride);
        if (role == AFN_IMAGE_COLOR) {
            if (v.components == 4)
                afnSetFilterImage(f, AFN_IMAGE_ALPHA, static_cast<char*>(v.ptr) + 3 * sizeof(float),
                    AFN_FORMAT_FLOAT, w, h, 0, v.pixelStride, v.rowStride);
            else
                afnUnsetFilterImage(f, AFN_IMAGE_ALPHA);
        }
    }
    out.resize(size_t(w) * h * 4);
    afnSetFilterImage(f, AFN_IMAGE_OUTPUT, out.data(), AFN_FORMAT_FLOAT4, w, h, 0, 0, 0);
    // The Pass clip (Output = Pass): denoised with the beauty into a buffer of its own, then
    // returned in the beauty's place with the beauty's alpha.
    const std::string passName = std::string(AFN_IMAGE_PASS_PREFIX) + "pass";
    const bool pass = std::any_of(req.inputs.begin(), req.inputs.end(),
        [&](const InputClip& in) { return passName == in.role; });
    const std::string passOutput = std::string(AFN_IMAGE_PASS_OUTPUT_PREFIX) + "pass";
    if (pass) {
        m_passOut.resize(size_t(w) * h * 3);
        afnSetFilterImage(
            f, passOutput.c_str(), m_passOut.data(), AFN_FORMAT_FLOAT3, w, h, 0, 0, 0);
    }
    applySettings(settings, f);
    if (methodHasParam(settings.method, AFN_CONVENTION_MOTION_Y_UP))
        afnSetFilterBool(f, AFN_CONVENTION_MOTION_Y_UP, true);
    if (methodHasParam(settings.method, AFN_CONVENTION_MOTION_SCALE))
        afnSetFilterFloat(f, AFN_CONVENTION_MOTION_SCALE, static_cast<float>(req.renderScale));
    checkError("setting the afn inputs");
    afnCommitFilter(f);
    checkError("afn commit");
    afnExecuteFilter(f);
    for (const InputClip& in : req.inputs)
        afnUnsetFilterImage(f, in.role);
    afnUnsetFilterImage(f, AFN_IMAGE_ALPHA);
    afnUnsetFilterImage(f, AFN_IMAGE_OUTPUT);
    afnUnsetFilterImage(f, passOutput.c_str());
    checkError("afn execute");
    if (pass)
        for (size_t i = 0; i < size_t(w) * h; ++i)
            for (int c = 0; c < 3; ++c)
                out[i * 4 + c] = m_passOut[i * 3 + c];
    if (settings.method == "afn") {
        // The trained model afn chose for the connected clips' inputs, logged when it changes.
        const char* model = afnGetFilterString(f, AFN_STAT_AFN_MODEL);
        if (model && m_afnModel != model) {
            m_afnModel = model;
            postNote(req.instance, "afn: " + m_afnModel);
        }
    }
}

} // namespace afnofx
