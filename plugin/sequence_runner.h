// SPDX-License-Identifier: Apache-2.0
// Per-instance frame cache and history: a frame requested right after the one the filter stands
// at continues the history; any other request replays a bounded window of earlier frames.
#pragma once

#include "param_table.h"

#include <afn/afn.hpp>

#include <deque>
#include <string>
#include <vector>

namespace afnofx {

/// Input clip roles, in the library's image names.
struct InputClip {
    const char* role; ///< "color", "albedo", "normal", "depth", "position" or "motion"
    OfxImageClipHandle clip; ///< a connected clip
};

/// What one render asks for, apart from the time.
struct FrameRequest {
    OfxImageEffectHandle instance = nullptr; ///< for abort checks
    std::vector<InputClip> inputs; ///< connected clips; "color" first
    OfxRectI window {}; ///< processed pixels (the Source RoD at render scale)
    OfxRectD windowCanonical {}; ///< the same in canonical coordinates (clipGetImage)
    double renderScale = 1.0; ///< x render scale (pixel vectors scale with it)
    /// First frame the history may use: the Source clip's first frame, or the start frame when
    /// that is set and later.
    double historyStart = 0.0;
};

/// Number of earlier frames the result at `time` replays after a jump: min(historyFrames, whole
/// frames from `historyStart` to `time`); 0 without history (temporal off, or `time` before
/// `historyStart`). Frames rendered in order continue the history instead (see
/// SequenceRunner::frame).
int replayFrames(double time, const Settings& settings, double historyStart);

/// Thrown when the host asked to abort.
struct Aborted { };

/// One afn filter advanced frame by frame plus the outputs of recent frames. Not thread-safe:
/// the instance serialises calls with its mutex.
class SequenceRunner {
public:
    /// Output of frame `time` as packed top-down RGBA floats over request.window.
    /// Throws OfxError on failures (message names the input) and Aborted.
    const std::vector<float>& frame(double time, const Settings& settings, const FrameRequest& req);
    /// Drop the history and every cached output (PurgeCaches, parameter changes).
    void clear();

private:
    void runFrame(
        double time, const Settings& settings, const FrameRequest& req, std::vector<float>& out);
    std::vector<float>& storeSlot(const std::string& key, double time);
    void checkError(const char* what);
    void loadWeights(const Settings& settings);
    /// Create the filter of `settings.method` on the device `settings.device` asks for (auto: CUDA
    /// when there is one and the method runs there, else the CPU with a note in the host's log).
    void createFilter(const Settings& settings, OfxImageEffectHandle instance);
    /// The filter on the CUDA device (true); false with the reason in `why` when auto falls back
    /// to the CPU. Throws OfxError when cuda was chosen and cannot serve.
    bool openOnCuda(const Settings& settings, std::string& why);

    afn::DeviceRef m_device;
    std::string m_deviceChoice; ///< settings.device the device and filter were made for
    afn::FilterRef m_filter;
    std::string m_filterMethod;
    std::string m_filterWeights; ///< path and stamp of the weights set on the filter
    std::string m_stateKey; ///< key of the frames the filter's history was built from
    double m_stateTime = 0.0; ///< last frame the filter executed
    bool m_hasState = false;
    struct Result {
        std::string key;
        double time;
        std::vector<float> rgba;
    };
    std::deque<Result> m_results; ///< recent outputs, oldest first
    std::vector<std::vector<float>> m_scratch;
    std::vector<float> m_passOut; ///< the denoised Pass clip (Output = Pass)
    std::string m_afnModel; ///< the afn path last logged (AFN_STAT_AFN_MODEL)
};

} // namespace afnofx
