// SPDX-License-Identifier: Apache-2.0
// afn public C API: opaque handles, named parameters, set -> commit -> execute.
//
// Conventions (stated once, they hold for every function below):
// - No function throws or aborts. A failing call records an error code and a message on its device
//   (or, for calls made with a NULL or invalid handle, in a per-thread slot read with
//   afnGetDeviceError(NULL, ...)). The first unqueried error is kept until it is read.
// - Images are described zero-copy as strided float buffers: pointer + byte offset + pixel stride +
//   row stride, in bytes. A stride of 0 means "packed". The row stride may be negative (bottom-up
//   images as OpenFX hosts hand them). Row 0 is the top row of the image as the caller sees it.
// - Filters are stateful only through their temporal history: afnExecuteFilter() processes one
//   frame and advances the history; afnResetFilter() drops it (scene cut, seek).
//
// Threads:
// - Every function may be called from any thread. Calls on one filter are serialised by the
//   library (a second caller waits); calls on different filters run concurrently, also when the
//   filters share a device.
// - afnSetDeviceInt() and afnCommitDevice() wait until the device's running executes have
//   finished, then apply; executes started later use the new settings. A device whose parameters
//   changed is uncommitted: afnNewFilter() and afnExecuteFilter() fail on it until it is committed.
// - Callbacks run on the thread of the call that triggers them: the error callback on the failing
//   call's thread, the progress callback on the executing thread (never concurrently for one
//   filter). A callback must not call back into afn with the same filter.
//
// ABI: handles are opaque; enum values are spaced by meaning and never reused; parameter, image
// and statistic names are the stable interface (the AFN_* name constants below). AFNParamInfo only
// grows at its end. AFN_VERSION_MAJOR changes when a binary built against an older header breaks.
#ifndef AFN_AFN_H
#define AFN_AFN_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#if defined(_WIN32)
#if defined(AFN_BUILDING_LIBRARY)
#define AFN_API __declspec(dllexport)
#else
#define AFN_API __declspec(dllimport)
#endif
#else
#define AFN_API __attribute__((visibility("default")))
#endif

#ifdef __cplusplus
extern "C" {
#endif

/// Version of the library the header belongs to; compare with afnGetDeviceInt(d, "version").
#define AFN_VERSION_MAJOR 0
#define AFN_VERSION_MINOR 1
#define AFN_VERSION_PATCH 0
#define AFN_VERSION (AFN_VERSION_MAJOR * 10000 + AFN_VERSION_MINOR * 100 + AFN_VERSION_PATCH)

/// Error codes. Values are spaced by meaning and never reused.
typedef enum AFNError {
    AFN_ERROR_NONE = 0, ///< no error
    AFN_ERROR_UNKNOWN = 1, ///< unexpected failure inside the library
    AFN_ERROR_INVALID_ARGUMENT = 2, ///< bad handle, name, value or image description
    AFN_ERROR_INVALID_OPERATION = 3, ///< call not allowed in the current state (e.g. uncommitted)
    AFN_ERROR_OUT_OF_MEMORY = 4, ///< an allocation failed
    AFN_ERROR_UNSUPPORTED = 5, ///< a valid request this build or device cannot serve
    AFN_ERROR_CANCELLED = 6, ///< the progress callback asked to stop
} AFNError;

/// Pixel formats of image buffers. Half formats are reserved (257+).
typedef enum AFNFormat {
    AFN_FORMAT_UNDEFINED = 0,
    AFN_FORMAT_FLOAT = 1, ///< 1 x float32
    AFN_FORMAT_FLOAT2 = 2, ///< 2 x float32
    AFN_FORMAT_FLOAT3 = 3, ///< 3 x float32
    AFN_FORMAT_FLOAT4 = 4, ///< 4 x float32 (the 4th channel is ignored on inputs except "alpha")
} AFNFormat;

/// Device types. The CUDA device exists only in builds with CUDA (afnNewDevice fails with
/// AFN_ERROR_UNSUPPORTED otherwise, and when no suitable GPU is present, saying why).
typedef enum AFNDeviceType {
    AFN_DEVICE_TYPE_DEFAULT = 0, ///< the CPU (the reference device; results do not depend on it)
    AFN_DEVICE_TYPE_CPU = 1, ///< the CPU, on a oneTBB thread arena
    /// An NVIDIA GPU of compute capability 9.0 or newer (Hopper). Only the "afn" method runs there
    /// (afnNewFilter fails with AFN_ERROR_UNSUPPORTED for the others); its results match the CPU's
    /// within the half-precision tolerance of docs/gpu.md. "numThreads" sizes the CPU threads that
    /// gather the inputs.
    AFN_DEVICE_TYPE_CUDA = 3,
} AFNDeviceType;

// ---- Names ------------------------------------------------------------------------------------
// The names a filter knows, as constants (the strings are the interface; both spellings work).

/// Input images (afnSetFilterImage).
#define AFN_IMAGE_COLOR "color" ///< noisy beauty, linear RGB (required)
#define AFN_IMAGE_ALBEDO "albedo" ///< albedo, [0, 1]
#define AFN_IMAGE_NORMAL "normal" ///< shading normal (space: AFN_CONVENTION_NORMAL_SPACE)
#define AFN_IMAGE_DEPTH "depth" ///< linear depth (kind: AFN_CONVENTION_DEPTH_KIND)
#define AFN_IMAGE_POSITION "position" ///< world position
#define AFN_IMAGE_MOTION "motion" ///< motion vectors (AFN_CONVENTION_MOTION_*)
#define AFN_IMAGE_ALPHA "alpha" ///< coverage, passed through to a FLOAT4 output
/// Work mask (1 channel; a wider format is read in its first channel): pixels where it is <= 0 (or
/// NaN) need no denoising and take the method's cheap path when "skip" is on
/// (docs/work-skipping.md).
#define AFN_IMAGE_MASK "mask"
/// Output image.
#define AFN_IMAGE_OUTPUT "output"
/// Prefix of a method's feature outputs ("feature.<name>", see afnGetFilterTypeFeature).
#define AFN_IMAGE_FEATURE_PREFIX "feature."
/// Light-path passes denoised with the beauty (docs/passes.md), any method: "pass.<name>" is an
/// additive light pass (FLOAT3/FLOAT4), "passFactor.<name>" its optional colour factor (the pass
/// adds pass x factor to the beauty, e.g. Blender's DiffDir x DiffCol), "passOutput.<name>" where
/// the denoised pass goes (needs "output"; may be the pass's own buffer). Denoised passes that
/// add up to the beauty add up to "output".
#define AFN_IMAGE_PASS_PREFIX "pass."
#define AFN_IMAGE_PASS_FACTOR_PREFIX "passFactor."
#define AFN_IMAGE_PASS_OUTPUT_PREFIX "passOutput."
/// Parameters every filter has: the conventions of the bound inputs.
#define AFN_CONVENTION_NORMAL_SPACE "normal.space"
#define AFN_CONVENTION_DEPTH_KIND "depth.kind"
#define AFN_CONVENTION_MOTION_DIRECTION "motion.direction"
#define AFN_CONVENTION_MOTION_Y_UP "motion.yUp"
#define AFN_CONVENTION_MOTION_UNITS "motion.units"
#define AFN_CONVENTION_MOTION_SCALE "motion.scale"
#define AFN_CONVENTION_COLOR_DEMODULATED "color.demodulated"
/// Quality of the auxiliary buffers (albedo, normal, depth): "auto" (default), "clean", "noisy"
/// (a parameter of every method that demodulates; lib/core/stages/aux_prefilter.h).
#define AFN_PARAM_AUX "aux"
/// Samples per pixel of the colour input (int, 0 = unknown; the same methods): the afn method
/// picks its model by it, and from AFN_AUX_TRUSTED_SPP on "aux=auto" uses the auxiliary buffers as
/// given, the albedo's grain limited over time (the speckle test cannot tell their remaining noise
/// from fine texture there).
#define AFN_PARAM_SPP "spp"
#define AFN_AUX_TRUSTED_SPP 16
/// Work skipping, parameters of every method (docs/work-skipping.md): "skip" (bool, default true)
/// lets pixels that need no denoising (depth non-finite or >= "denoisingRange" (float, scene units,
/// default 1e9), alpha 0, AFN_IMAGE_MASK <= 0) take the method's cheap path where it has one
/// (svgf, bmfr, afn on the CPU; the help of "skip" says what each method does); the pixels that
/// need denoising come out bit-identical to skip = false.
#define AFN_PARAM_SKIP "skip"
#define AFN_PARAM_DENOISING_RANGE "denoisingRange"
/// History trust (float, 0-4, default 1; every method that keeps a temporal history): how fast a
/// change of the lighting cuts the history where the geometry still matches (a light moved or
/// switched, a shadow or an emitter changed). 0 keeps it as the original methods do
/// (lib/core/stages/history_trust.h).
#define AFN_PARAM_ANTILAG "antilag"
/// The afn method's network arithmetic: "auto" (default: bf16 where the CPU has AVX512_BF16),
/// "fp32", "bf16" (emulated where the CPU lacks AVX512_BF16: the same results, fp32's speed).
#define AFN_PARAM_PRECISION "precision"
/// Cost/accuracy tier: "fast", "balanced" (default: the method as without the parameter), "high"
/// (a parameter of every denoising method; what each tier does is in its help text and
/// docs/quality.md, lib/core/filter/quality.h).
#define AFN_PARAM_QUALITY "quality"
/// Array parameters (afnSetFilterFloats).
#define AFN_ARRAY_VIEW_PROJECTION "viewProjection"
#define AFN_ARRAY_PIXEL_OFFSET "pixelOffset"
/// Data parameters (afnSetFilterData).
#define AFN_DATA_WEIGHTS "weights"
/// Read-only values of a filter (afnGetFilterInt).
#define AFN_STAT_NON_FINITE "stats.nonFinite"
#define AFN_STAT_NEGATIVE "stats.negative"
#define AFN_STAT_FRAME_INDEX "frameIndex"
#define AFN_STAT_WIDTH "width"
#define AFN_STAT_HEIGHT "height"
/// 1 when the auxiliary buffers are prefiltered as noisy for the current history, else 0.
#define AFN_STAT_AUX_NOISY "stats.auxNoisy"
/// 1 when, from AFN_AUX_TRUSTED_SPP with aux=auto, the buffers are used as given but the albedo's
/// grain is limited over time (within 10 % of each given value), else 0.
#define AFN_STAT_AUX_GRAIN_LIMITED "stats.auxGrainLimited"
/// Share in [0, 1] of speckle pixels (afnEstimateAuxNoise) of the last frame's albedo, normal and
/// depth inputs as given; -1 when the input is absent (afnGetFilterFloat). A history decided clean
/// measures them when first asked for after a frame (a pass over the three inputs), not on every
/// frame.
#define AFN_STAT_ALBEDO_SPECKLE "stats.albedoSpeckle"
#define AFN_STAT_NORMAL_SPECKLE "stats.normalSpeckle"
#define AFN_STAT_DEPTH_SPECKLE "stats.depthSpeckle"
/// Share in [0, 1] of the last frame's pixels that needed no denoising (work skipping; 0 with
/// skip = false) (afnGetFilterFloat).
#define AFN_STAT_SKIPPED "stats.skipped"
/// Share in [0, 1] of the last frame's pixels whose temporal history was cut because the lighting
/// changed (history trust below one half; parameter "antilag"); 0 for methods without a history
/// (afnGetFilterFloat). The per-pixel trust is the feature output "historyTrust".
#define AFN_STAT_HISTORY_CUT "stats.historyCut"
/// Share in [0, 1] of the last frame's pixels to which the detail restoration gave back more than
/// half of the frame's own difference from the output (parameter "restore"); 0 where it did not
/// run (afnGetFilterFloat).
#define AFN_STAT_RESTORED "stats.restored"
/// Pixels of the last frame whose highlight bypassed the method's spatial filter and was added
/// back at its own pixel (parameter "highlights"; afnGetFilterFloat); 0 for methods without the
/// bypass.
#define AFN_STAT_HIGHLIGHTS "stats.highlights"
/// The inputs the method reads that the last frame lacked, with what each is for, e.g.
/// "normal (edge-stopping); motion or position with a camera (reprojection: ...)"; "" when none
/// (afnGetFilterString). The method still runs, with less to go on.
#define AFN_STAT_MISSING_INPUTS "stats.missingInputs"
/// The "afn" method's path for the last frame (afnGetFilterString): the input set of the
/// trained model chosen for the frame's inputs, temporal or single-frame, and the frame inputs it
/// does not use, e.g. "model color+albedo+normal, single-frame (no temporal branch: no motion or
/// position); not used: depth"; "" before the first frame.
#define AFN_STAT_AFN_MODEL "stats.afn.model"
/// The "afn" method on the CPU, last execute (afnGetFilterFloat): wall-clock milliseconds and GFLOP
/// (2 x multiply-adds of the layers and 7x7 filters at the padded size; softmax, pooling and tone
/// map not counted) of the network's stages: prediction (input preparation + encoder-decoder),
/// filtering (kernel heads, softmax, 7x7 filtering, fusion), refinement. "stats.afn.avx512" is 1
/// when the AVX-512 kernels ran (chosen at run time), 0 for the portable ones.
#define AFN_STAT_AFN_PREDICTION_MS "stats.afn.prediction.ms"
#define AFN_STAT_AFN_PREDICTION_GFLOP "stats.afn.prediction.gflop"
/// Of AFN_STAT_AFN_PREDICTION_MS, the milliseconds that prepare the network input (tone map,
/// input channels, the 1-spp colour's pooling: no FLOP counted); 0 where not measured.
#define AFN_STAT_AFN_PREDICTION_INPUT_MS "stats.afn.prediction.inputMs"
#define AFN_STAT_AFN_FILTERING_MS "stats.afn.filtering.ms"
#define AFN_STAT_AFN_FILTERING_GFLOP "stats.afn.filtering.gflop"
#define AFN_STAT_AFN_REFINEMENT_MS "stats.afn.refinement.ms"
#define AFN_STAT_AFN_REFINEMENT_GFLOP "stats.afn.refinement.gflop"
#define AFN_STAT_AFN_AVX512 "stats.afn.avx512"
/// The arithmetic of the network's convolutions from the committed settings on this CPU
/// (parameter AFN_PARAM_PRECISION; AFN large always fp32): 16 for bfloat16 operands (with fp32
/// sums), 32 for fp32; "stats.afn.bf16Hardware" is 1 when that bf16 runs on bf16 instructions
/// (AVX512_BF16 or AMX), 0 when emulated or not bf16; "stats.afn.bf16Amx" is 1 when it runs on
/// AMX tiles.
#define AFN_STAT_AFN_PRECISION "stats.afn.precision"
#define AFN_STAT_AFN_BF16_HARDWARE "stats.afn.bf16Hardware"
#define AFN_STAT_AFN_BF16_AMX "stats.afn.bf16Amx"

/// Types of filter parameters, as reported by afnGetFilterTypeParam().
typedef enum AFNParamType {
    AFN_PARAM_BOOL = 1,
    AFN_PARAM_INT = 2,
    AFN_PARAM_FLOAT = 3,
    AFN_PARAM_STRING = 4, ///< one of a fixed set of choices, '|'-separated in AFNParamInfo::choices
} AFNParamType;

/// Description of one filter parameter (name, type, default, range, help).
typedef struct AFNParamInfo {
    const char* name; ///< name used with afnSetFilter*()
    AFNParamType type; ///< value type
    double defaultValue; ///< default for bool/int/float parameters
    double minValue; ///< smallest accepted value (bool/int/float)
    double maxValue; ///< largest accepted value (bool/int/float)
    const char* defaultString; ///< default for string parameters, else ""
    const char* choices; ///< '|'-separated accepted strings, else ""
    const char* label; ///< short human label
    const char* help; ///< one-line description with units and source of the default
} AFNParamInfo;

/// Description of one feature output: an intermediate image a method can write besides "output"
/// (for learned methods, the inputs of the network exactly as it sees them; training tools read
/// them so that they never re-implement the input preparation).
typedef struct AFNFeatureInfo {
    const char* name; ///< bound as AFN_IMAGE_FEATURE_PREFIX + name
    int channels; ///< 1 or 3; the bound image needs at least this many
    const char* help; ///< one line: what the values are (range, space, scaling)
} AFNFeatureInfo;

typedef struct AFNDeviceImpl* AFNDevice;
typedef struct AFNFilterImpl* AFNFilter;

/// Called on every error recorded on a device (from the thread that made the failing call).
typedef void (*AFNErrorFunction)(void* userPtr, AFNError code, const char* message);
/// Called with progress in [0, 1]; return false to cancel the running execute.
typedef bool (*AFNProgressMonitorFunction)(void* userPtr, double progress);

// ---- Device -------------------------------------------------------------------------------------

/// Create a device of the given type (reference count 1). Returns NULL on failure (error in this
/// thread's slot: AFN_ERROR_UNSUPPORTED when the build or the machine has no such device).
AFN_API AFNDevice afnNewDevice(AFNDeviceType type);
/// Add a reference to the device.
AFN_API void afnRetainDevice(AFNDevice device);
/// Drop a reference; the device is destroyed when the last reference goes.
AFN_API void afnReleaseDevice(AFNDevice device);
/// Set an integer parameter: "numThreads" (0 = all cores, default). Uncommits the device.
AFN_API void afnSetDeviceInt(AFNDevice device, const char* name, int value);
/// Get an integer parameter: "numThreads", "type" (AFNDeviceType), "version" (AFN_VERSION).
AFN_API int afnGetDeviceInt(AFNDevice device, const char* name);
/// Register an error callback (NULL to remove).
AFN_API void afnSetDeviceErrorFunction(AFNDevice device, AFNErrorFunction func, void* userPtr);
/// Apply device parameters; must be called once before creating filters.
AFN_API void afnCommitDevice(AFNDevice device);
/// Return and clear the first unqueried error of the device (NULL device: this thread's slot).
/// *outMessage, if outMessage is not NULL, points to a message valid until the next call.
AFN_API AFNError afnGetDeviceError(AFNDevice device, const char** outMessage);

// ---- Filter types (introspection) ---------------------------------------------------------------

/// Number of filter types this build offers ("identity", "ta", "svgf", "bmfr", ...).
AFN_API int afnGetNumFilterTypes(void);
/// Name of the i-th filter type, NULL if out of range.
AFN_API const char* afnGetFilterTypeName(int index);
/// One-line description of a filter type, NULL if unknown.
AFN_API const char* afnGetFilterTypeDescription(const char* type);
/// True when filters of this type run as created: the method needs no data, or this build embeds
/// its trained weights. False for a learned method without built-in weights (set them with
/// afnSetFilterData(filter, AFN_DATA_WEIGHTS, ...)) and for unknown types.
AFN_API bool afnIsFilterTypeReady(const char* type);
/// Number of feature outputs of a filter type (0 for most methods), -1 if unknown.
AFN_API int afnGetFilterTypeNumFeatures(const char* type);
/// Fill *info with the index-th feature output of a type; false if out of range. Strings are
/// static.
AFN_API bool afnGetFilterTypeFeature(const char* type, int index, AFNFeatureInfo* info);
/// Number of parameters of a filter type (common input-convention parameters included), -1 if
/// unknown.
AFN_API int afnGetFilterTypeNumParams(const char* type);
/// Fill *info with the index-th parameter of a type; false if out of range. Strings are static.
AFN_API bool afnGetFilterTypeParam(const char* type, int index, AFNParamInfo* info);

// ---- Filter -------------------------------------------------------------------------------------

/// Create a filter of the given type on a committed device. Returns NULL on failure.
AFN_API AFNFilter afnNewFilter(AFNDevice device, const char* type);
/// Add a reference to the filter.
AFN_API void afnRetainFilter(AFNFilter filter);
/// Drop a reference; the filter is destroyed when the last reference goes.
AFN_API void afnReleaseFilter(AFNFilter filter);

/// Bind an image. Inputs: "color" (required), "albedo", "normal", "depth", "position", "motion",
/// "alpha". Output: "output" (FLOAT3 or FLOAT4; with FLOAT4 the 4th channel is passed through from
/// "alpha" or set to 1). Feature outputs: "feature.<name>" (see afnGetFilterTypeFeature). A filter
/// needs "output" or at least one feature output; with feature outputs only, the method stops once
/// they are written (a learned method then runs without weights). Strides in bytes; 0 = packed. The
/// buffer must stay valid until it is unset or replaced; the filter never keeps pointers into it
/// across afnExecuteFilter() calls.
AFN_API void afnSetFilterImage(AFNFilter filter, const char* name, void* ptr, AFNFormat format,
    size_t width, size_t height, size_t byteOffset, size_t pixelByteStride,
    ptrdiff_t rowByteStride);
/// Unbind an image.
AFN_API void afnUnsetFilterImage(AFNFilter filter, const char* name);

/// Set a parameter by name (see afnGetFilterTypeParam for names, ranges and defaults).
AFN_API void afnSetFilterBool(AFNFilter filter, const char* name, bool value);
AFN_API void afnSetFilterInt(AFNFilter filter, const char* name, int value);
AFN_API void afnSetFilterFloat(AFNFilter filter, const char* name, float value);
AFN_API void afnSetFilterString(AFNFilter filter, const char* name, const char* value);
/// Set an array parameter: "viewProjection" (16 floats, row-vector convention clip = [p,1]·M, the
/// current frame's camera, as in the BMFR dataset's camera_matrices.h), "pixelOffset" (2 floats).
AFN_API void afnSetFilterFloats(
    AFNFilter filter, const char* name, const float* values, size_t count);
/// Set an opaque data blob: "weights" (a weights archive; the library copies it).
AFN_API void afnSetFilterData(
    AFNFilter filter, const char* name, const void* data, size_t byteSize);

/// Read a parameter or a statistic of the last execute: "stats.nonFinite" (input values replaced
/// because NaN/Inf), "stats.negative" (negative colour values clamped), "frameIndex" (frames since
/// the last reset), "width", "height", "stats.auxNoisy", "stats.auxGrainLimited" and
/// "stats.*Speckle" (AFN_STAT_*).
AFN_API bool afnGetFilterBool(AFNFilter filter, const char* name);
AFN_API int afnGetFilterInt(AFNFilter filter, const char* name);
AFN_API float afnGetFilterFloat(AFNFilter filter, const char* name);
/// The string is owned by the filter and valid until the parameter changes (or the next execute,
/// for AFN_STAT_MISSING_INPUTS).
AFN_API const char* afnGetFilterString(AFNFilter filter, const char* name);

/// Register a progress callback (NULL to remove).
AFN_API void afnSetFilterProgressMonitorFunction(
    AFNFilter filter, AFNProgressMonitorFunction func, void* userPtr);
/// Validate the bound images and parameters; errors name the offending input.
AFN_API void afnCommitFilter(AFNFilter filter);
/// Denoise one frame: read the inputs, write "output", advance the temporal history.
AFN_API void afnExecuteFilter(AFNFilter filter);
/// Drop the temporal history; the next execute behaves as the first frame of a sequence.
AFN_API void afnResetFilter(AFNFilter filter);

// ---- Image-quality metrics ----------------------------------------------------------------------
// Conventions (docs/metrics.md): compare remodulated outputs with references (albedo included).
// T(x) = clip(max(x, 0)^(1/2.2), 0, 1). Only the first 3 channels of a pixel are compared.
// SSIM: skimage defaults (7x7 uniform window, K1 0.01, K2 0.03, sample covariance, 3-pixel border
// left out, per channel then averaged) with data_range 1. Any NaN/Inf in either image is counted
// and makes every metric of that frame NaN. A sequence's value is the mean of its per-frame values.
// Images are packed rows of `width * pixelFloatStride` floats (pixelFloatStride >= 3).

/// Metrics of one test image against its reference.
typedef struct AFNMetrics {
    double psnr; ///< dB, 10 log10(1 / MSE) on T(x); +inf for identical images
    double ssim; ///< [-1, 1] on T(x); 1 for identical images
    double rmse; ///< [0, 1], sqrt(MSE) on T(x)
    double smape; ///< [0, 1], AFN Eq. 5 on linear values, eps = 1e-3
    double rmseLinear; ///< >= 0, sqrt(MSE) on linear values
    double smapeTonemapped; ///< [0, 1], AFN Eq. 5 on T(x), eps = 1e-3
    double psnr8; ///< PSNR on T(x) quantised to 8 bits (round(255 T) / 255), as on PNGs
    double ssim8; ///< SSIM on T(x) quantised to 8 bits
    double rmse8; ///< RMSE on T(x) quantised to 8 bits
    int64_t nonFiniteTest; ///< NaN/Inf values found in the test image (first 3 channels)
    int64_t nonFiniteReference; ///< NaN/Inf values found in the reference image
} AFNMetrics;

/// Temporal stability of frame t given frame t-1: with e = (T(o_t) - T(o_t-1)) - (T(r_t) -
/// T(r_t-1)) per value (o: test, r: reference), the mean |e| and the PSNR of e (R = 1).
typedef struct AFNTemporalMetrics {
    double gradientError; ///< >= 0, mean |e| (0 = the test flickers exactly as the reference)
    double gradientPsnr; ///< dB, 10 log10(1 / mean e^2); +inf when e == 0 everywhere
    int64_t nonFinite; ///< NaN/Inf values in the four images; makes both fields NaN
} AFNTemporalMetrics;

/// Compute the metrics of `test` against `reference` on the device's threads. Returns false (and
/// records an error on the device) for a bad device, NULL pointers, zero size or a stride < 3.
/// Results do not depend on the device's thread count.
AFN_API bool afnComputeMetrics(AFNDevice device, const float* test, const float* reference,
    size_t width, size_t height, size_t pixelFloatStride, AFNMetrics* out);
/// Compute the temporal-gradient error of (testPrev, test) against (referencePrev, reference).
/// Same image layout and error rules as afnComputeMetrics.
AFN_API bool afnComputeTemporalMetrics(AFNDevice device, const float* testPrev, const float* test,
    const float* referencePrev, const float* reference, size_t width, size_t height,
    size_t pixelFloatStride, AFNTemporalMetrics* out);

// ---- Auxiliary-buffer noise
// ----------------------------------------------------------------------

/// Noise estimate of an auxiliary buffer (lib/core/stages/aux_noise.h): the share of "speckle"
/// pixels, which differ from all 8 neighbours by more than a threshold (albedo 10 % relative;
/// unit normals 0.3 apart; depth 5 % relative, pixels without a surface ignored). A clean
/// (first-hit) buffer has almost none; one that follows specular bounces or carries DOF or motion
/// blur at low sample counts has many. The "aux=auto" decision uses the same number.
typedef struct AFNAuxNoise {
    double speckle; ///< [0, 1] share of speckle pixels
    bool noisy; ///< speckle above the "auto" threshold (0.5 %); aux=auto also needs the colour
                ///< below AFN_AUX_TRUSTED_SPP samples per pixel
} AFNAuxNoise;

/// Estimate the noise of an auxiliary buffer of `role` "albedo", "normal" (3 floats read per
/// pixel) or "depth" (1 float): packed rows of `width * pixelFloatStride` floats. Returns false
/// (and records an error on the device) for a bad device or role, NULL pointers, zero size or a
/// stride too small for the role.
AFN_API bool afnEstimateAuxNoise(AFNDevice device, const char* role, const float* data,
    size_t width, size_t height, size_t pixelFloatStride, AFNAuxNoise* out);

#ifdef __cplusplus
}
#endif

#endif // AFN_AFN_H
