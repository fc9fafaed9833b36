// SPDX-License-Identifier: Apache-2.0
// Base of every denoising method. It owns the image bindings and parameters, validates them at
// commit, converts the bound buffers into a canonical Frame once per execute (filter/gather.cpp),
// runs the shared stages the method asks for, calls the method, and writes the method's radiance
// into the bound output. It also owns the temporal history's life: the first frame after creation
// or a reset starts every stage and the method from an empty history.
//
// Per execute:  gather -> work mask -> [aux prefilter: geometry] -> [reproject] -> [aux prefilter:
// albedo]
//               -> [demodulate] -> [accumulate] -> denoise() -> output -> [restore]
// (the aux prefilter runs with demodulation; stages/aux_prefilter.h; the detail restoration,
// stages/detail_restore.h, on the output of the methods that demodulate, from the frame's colour
// as gathered)
#pragma once

#include "base/params.h"
#include "filter/conventions.h"
#include "filter/frame.h"
#include "filter/work_mask.h"
#include "stages/aux_prefilter.h"
#include "stages/detail_restore.h"
#include "stages/pass_transfer.h"
#include "stages/temporal_accumulation.h"

#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace afn {

/// A caller's image buffer as given to afnSetFilterImage (strides in bytes, already resolved).
struct ImageBinding {
    void* ptr = nullptr;
    AFNFormat format = AFN_FORMAT_UNDEFINED;
    int width = 0;
    int height = 0;
    std::size_t byteOffset = 0;
    std::ptrdiff_t pixelStride = 0;
    std::ptrdiff_t rowStride = 0;
    int channels() const { return static_cast<int>(format); }
    ImageView view() const;
};

/// Names of the bindable input images (AFN_IMAGE_* except the output).
const std::vector<std::string>& inputImageNames();

struct FilterType;

/// An intermediate image a method can write besides its output (AFNFeatureInfo in afn.h).
struct FeatureOutput {
    std::string name; ///< bound as AFN_IMAGE_FEATURE_PREFIX + name
    int channels = 3; ///< 1 or 3
    std::string help;
};

/// An input a method reads besides the colour (FilterType::inputs). Methods run without it, at a
/// cost the caller should hear about (afnGetFilterString(filter, AFN_STAT_MISSING_INPUTS)).
struct InputUse {
    std::vector<std::string> anyOf; ///< image names, any of which serves ("depth", "position")
    std::string purpose; ///< what it is for / what happens without it, one short phrase
    bool positionNeedsCamera = false; ///< "position" in anyOf serves only with a camera
};

/// The inputs of `type` that `frame` lacks, e.g. "normal (edge-stopping); motion (reprojection:
/// without it the camera is taken as static)"; "" when nothing is missing (input_uses.cpp).
std::string missingInputs(const FilterType& type, const Frame& frame);

/// The shared stages a method composes; the Filter base runs them before denoise().
struct StageNeeds {
    /// Reprojection of the previous frame's geometry onto this one.
    enum class Reproject { None, Bilinear, BilinearWithBoxFallback };

    bool demodulate = false; ///< irradiance(): colour / albedo (stages/demodulate.h), after the
                             ///< aux prefilter (stages/aux_prefilter.h, parameter "aux")
    Reproject reproject = Reproject::None; ///< reprojector(): per-pixel history taps
    bool accumulate = false; ///< accumulator(): BMFR temporal accumulation (needs
                             ///< demodulate and a reprojection)
};

class Filter {
public:
    virtual ~Filter() = default;

    void setImage(const std::string& name, const ImageBinding& binding);
    void unsetImage(const std::string& name);
    ParamSet& params() { return m_params; }
    const ParamSet& params() const { return m_params; }
    void setFloats(const std::string& name, const std::vector<float>& values);
    virtual void setData(const std::string& name, const void* data, std::size_t size);
    void setProgressMonitor(std::function<bool(double)> fn) { m_progress = std::move(fn); }

    void markDirty() { m_committed = false; }
    void commit();
    void execute();
    void reset();

    int frameIndex() const { return m_frameIndex; }
    const InputStats& lastStats() const { return m_stats; }
    /// The method's inputs the last frame lacked (missingInputs(); "" when none).
    const std::string& lastMissingInputs() const { return m_missingInputs; }
    /// Share of the last frame's pixels that needed no denoising (filter/work_mask.h).
    double lastSkippedShare() const { return m_skipped; }
    /// What the aux prefilter measured and decided on the last frame (methods that demodulate).
    /// A clean history's speckle shares are measured here, when first asked for. A filter whose
    /// prefilter runs elsewhere (a GPU) gives its own.
    virtual const AuxReport& auxReport() const;
    /// The aux prefilter's decisions for the last frame (auxReport()'s flags, without measuring
    /// pending shares).
    virtual bool auxNoisy() const { return m_aux.report().noisy; }
    virtual bool auxGrainLimited() const { return m_aux.report().grainLimited; }
    int width() const { return m_frame.width; }
    int height() const { return m_frame.height; }
    /// The history trust of the last frame (stages/history_trust.h): the accumulation stage's,
    /// or the method's own (svgf); nullptr for a method without one.
    virtual const HistoryTrust* historyTrust() const
    {
        return m_stages.accumulate ? &m_accumulator.trust() : nullptr;
    }
    /// Share of the last frame's pixels whose history was cut (HistoryTrust::cutShare(); 0
    /// without a history trust). A filter whose trust runs elsewhere (a GPU) gives its own.
    virtual double lastHistoryCutShare() const
    {
        const HistoryTrust* t = historyTrust();
        return t ? t->cutShare() : 0.0;
    }
    /// Pixels of the last frame whose highlight bypassed the method's spatial filter
    /// (stages/highlight_bypass.h; AFN_STAT_HIGHLIGHTS); 0 for methods without the bypass.
    virtual std::int64_t lastHighlightPixels() const { return 0; }
    /// Share of the last frame's pixels to which the detail restoration gave back more than half
    /// of the frame's own value (stages/detail_restore.h); 0 where it did not run.
    double lastRestoredShare() const { return m_restoreRan ? m_restore.restoredShare() : 0.0; }
    /// A method's own statistic of the last execute ("stats.afn.*"); false when it has none of
    /// that name.
    virtual bool statistic(const std::string& name, double& value) const { return false; }
    /// A method's own text statistic of the last execute ("stats.afn.model"); false when it has
    /// none of that name.
    virtual bool stringStatistic(const std::string& name, std::string& value) const
    {
        return false;
    }

protected:
    /// A filter of `type` (parameter table, stages, feature outputs); the type outlives it.
    explicit Filter(const FilterType& type);
    /// A filter of `type` whose base runs `stages` instead of the type's: a device filter that
    /// runs the shared stages itself passes StageNeeds {} (cuda/afn_cuda_filter.h).
    Filter(const FilterType& type, StageNeeds stages);

    /// Read the method's settings from params(); called at commit. Throw on invalid combinations.
    virtual void configure() { }
    /// Denoise one canonical frame into `out` (3 channels, frame size, preallocated). The stages
    /// the method asked for have run on this frame.
    virtual void denoise(const Frame& in, Image& out) = 0;
    /// Methods whose output is the remodulation (stages/demodulate.h) of a demodulated result may
    /// return that result here instead: the base then remodulates it straight into the bound
    /// output (no frame-size radiance image, one pass less) and does not call denoise(). nullptr
    /// (the default): the base calls denoise(). Called only when "output" is bound.
    virtual const Image* denoiseDemodulated(const Frame& in) { return nullptr; }
    /// Methods that keep their radiance result in an image of their own (e.g. as the next frame's
    /// history) may return it here (3 channels, frame size): the base writes it into the bound
    /// output and does not call denoise() (no frame-size copy in the base). nullptr (the
    /// default): the base calls denoise(). Called only when "output" is bound and
    /// denoiseDemodulated() returned nullptr.
    virtual const Image* denoiseRadiance(const Frame& in) { return nullptr; }
    /// True for a method whose output is the remodulated accumulation itself (ta): the base then
    /// writes the output in the accumulation's pass, row band by row band (the same values as
    /// denoiseDemodulated() returning accumulator().color(); the row data is still in cache),
    /// and calls neither denoiseDemodulated() nor denoise(). Only with StageNeeds::accumulate.
    virtual bool outputIsAccumulation() const { return false; }
    /// The sample count the method's filter was made for (afn: its model's, as chosen at
    /// commit): the detail restoration's auto runs from twice it (stages/detail_restore.h).
    virtual int samplesMadeFor() const { return 1; }
    /// Drop the method's own temporal history (the stages' is dropped by the base).
    virtual void resetHistory() { }
    /// Report progress in [0, 1]; throws Cancelled when the callback asks to stop.
    void reportProgress(double fraction) const;

    /// True when the caller bound "output" (false: only feature outputs are wanted).
    bool outputBound() const;
    /// True when the caller bound at least one feature output.
    bool anyFeatureBound() const;
    /// True when the caller bound the feature output `name`.
    bool featureBound(const std::string& name) const
    {
        return m_images.count(AFN_IMAGE_FEATURE_PREFIX + name) != 0;
    }
    /// True when the caller bound the image `name` (AFN_IMAGE_*), e.g. to choose a path at commit.
    bool imageBound(const std::string& name) const { return m_images.count(name) != 0; }
    /// True when the caller set a camera (AFN_ARRAY_VIEW_PROJECTION) for the next frame.
    bool cameraSet() const { return m_camera.valid; }
    /// Write the first channels of `image` (frame size) into the feature output `name` when the
    /// caller bound it; `name` must be one of the type's features.
    void writeFeature(const std::string& name, const Image& image) const;

    /// Results of the shared stages for the current frame. The demodulation runs in place:
    /// irradiance() is the frame's colour buffer (Frame::color holds the irradiance once the
    /// stage has run: no second frame-size colour image).
    const Image& irradiance() const { return m_frame.color; }
    /// irradiance() itself, writable: a method that has read the irradiance may write its own
    /// demodulated result (3 channels, frame size) in its place, e.g. as denoiseDemodulated()'s
    /// result (no frame-size image of its own). Nothing reads the frame's colour after the method.
    Image& irradianceForReuse() { return m_frame.color; }
    /// The accumulation stage's scratch image (TemporalAccumulator::scratch()) for use within the
    /// current frame; methods that ask for StageNeeds::accumulate only.
    Image& accumulatorScratch() { return m_accumulator.scratch(); }
    const Reprojector& reprojector() const { return m_reprojector; }
    const TemporalAccumulator& accumulator() const { return m_accumulator; }
    /// Replace the accumulation's settings commit() read from the parameters (from configure(),
    /// e.g. a minimum blend that depends on the chosen model; afn).
    void setAccumulationSettings(const AccumulationSettings& s) { m_accumulator.setSettings(s); }

private:
    void validateBindings() const;
    void runStages();
    void writeOutput(const Image& radiance) const;
    /// Denoise the bound passes with the frame's output (stages/pass_transfer.h).
    void runPassTransfer();
    /// writeOutput(remodulate(irradiance)) in one pass (denoiseDemodulated()).
    void writeRemodulated(const Image& irradiance) const;
    void writeRemodulatedRows(const Image& irradiance, int y0, int y1) const;
    /// runStages() writes the output in the accumulation's pass (outputIsAccumulation()).
    bool outputWrittenByStages() const;
    /// Write the "historyTrust" feature when it is bound.
    void writeTrustFeature();

    const FilterType& m_type;
    ParamSet m_params;
    StageNeeds m_stages;
    InputConventions m_conventions;
    WorkSettings m_work;
    double m_skipped = 0.0;
    std::map<std::string, ImageBinding> m_images;
    std::function<bool(double)> m_progress;
    Camera m_camera; ///< set for the next frame
    Camera m_prevCamera; ///< camera of the last executed frame
    bool m_committed = false;
    int m_frameIndex = 0;
    int m_prevWidth = 0, m_prevHeight = 0;
    std::string m_prevInputs; ///< which inputs the previous frame had (history consistency)
    Frame m_frame; ///< reused across frames: allocated once per resolution
    Image m_output;
    Image m_trustMap; ///< the "historyTrust" feature, only when it is bound
    InputStats m_stats;
    std::string m_missingInputs;
    AuxPrefilter m_aux;
    Reprojector m_reprojector;
    TemporalAccumulator m_accumulator;
    PassTransfer m_passTransfer;
    RestoreSettings m_restoreSettings;
    bool m_restoreOn = false; ///< restoreOn() for the committed parameters
    bool m_restoreRan = false; ///< on the last frame
    Image m_noisy; ///< the frame's colour as gathered, while the restoration is on
    DetailRestore m_restore;
};

/// Convert the bound images into a canonical frame (see filter/frame.h), counting sanitised values.
void gatherFrame(const std::map<std::string, ImageBinding>& images,
    const InputConventions& conventions, Frame& frame, InputStats& stats);

} // namespace afn
