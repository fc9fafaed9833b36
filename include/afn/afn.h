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
    AFN_ERROR_NONE = 0,              ///< no error
    AFN_ERROR_UNKNOWN = 1,           ///< unexpected failure inside the library
    AFN_ERROR_INVALID_ARGUMENT = 2,  ///< bad handle, name, value or image description
    AFN_ERROR_INVALID_OPERATION = 3, ///< call not allowed in the current state (e.g. uncommitted)
    AFN_ERROR_OUT_OF_MEMORY = 4,     ///< an allocation failed
    AFN_ERROR_UNSUPPORTED = 5,       ///< a valid request this build or device cannot serve
    AFN_ERROR_CANCELLED = 6,         ///< the progress callback asked to stop
} AFNError;

/// Pixel formats of image buffers. Half formats are reserved (257+).
typedef enum AFNFormat {
    AFN_FORMAT_UNDEFINED = 0,
    AFN_FORMAT_FLOAT = 1,  ///< 1 x float32
    AFN_FORMAT_FLOAT2 = 2, ///< 2 x float32
    AFN_FORMAT_FLOAT3 = 3, ///< 3 x float32
    AFN_FORMAT_FLOAT4 = 4, ///< 4 x float32 (the 4th channel is ignored on inputs except "alpha")
} AFNFormat;

/// Types of filter parameters, as reported by afnGetFilterTypeParam().
typedef enum AFNParamType {
    AFN_PARAM_BOOL = 1,
    AFN_PARAM_INT = 2,
    AFN_PARAM_FLOAT = 3,
    AFN_PARAM_STRING = 4, ///< one of a fixed set of choices, '|'-separated in AFNParamInfo::choices
} AFNParamType;

/// Description of one filter parameter (name, type, default, range, help).
typedef struct AFNParamInfo {
    const char* name;          ///< name used with afnSetFilter*()
    AFNParamType type;         ///< value type
    double defaultValue;       ///< default for bool/int/float parameters
    double minValue;           ///< smallest accepted value (bool/int/float)
    double maxValue;           ///< largest accepted value (bool/int/float)
    const char* defaultString; ///< default for string parameters, else ""
    const char* choices;       ///< '|'-separated accepted strings, else ""
    const char* label;         ///< short human label
    const char* help;          ///< one-line description with units and source of the default
} AFNParamInfo;

typedef struct AFNDeviceImpl* AFNDevice;
typedef struct AFNFilterImpl* AFNFilter;

/// Called on every error recorded on a device (from the thread that made the failing call).
typedef void (*AFNErrorFunction)(void* userPtr, AFNError code, const char* message);
/// Called with progress in [0, 1]; return false to cancel the running execute.
typedef bool (*AFNProgressMonitorFunction)(void* userPtr, double progress);

// ---- Device -------------------------------------------------------------------------------------

/// Create a CPU device (reference count 1). Returns NULL on failure.
AFN_API AFNDevice afnNewDevice(void);
/// Add a reference to the device.
AFN_API void afnRetainDevice(AFNDevice device);
/// Drop a reference; the device is destroyed when the last reference goes.
AFN_API void afnReleaseDevice(AFNDevice device);
/// Set an integer parameter: "numThreads" (0 = all cores, default), "verbose" (0..3).
AFN_API void afnSetDeviceInt(AFNDevice device, const char* name, int value);
/// Get an integer parameter: "numThreads", "verbose", "version" (AFN_VERSION of the library).
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
/// Number of parameters of a filter type (common input-convention parameters included), -1 if unknown.
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
/// "alpha" or set to 1). Strides in bytes; 0 = packed. The buffer must stay valid until it is
/// unset or replaced; the filter never keeps pointers into it across afnExecuteFilter() calls.
AFN_API void afnSetFilterImage(AFNFilter filter, const char* name, void* ptr, AFNFormat format,
                               size_t width, size_t height, size_t byteOffset,
                               size_t pixelByteStride, ptrdiff_t rowByteStride);
/// Unbind an image.
AFN_API void afnUnsetFilterImage(AFNFilter filter, const char* name);

/// Set a parameter by name (see afnGetFilterTypeParam for names, ranges and defaults).
AFN_API void afnSetFilterBool(AFNFilter filter, const char* name, bool value);
AFN_API void afnSetFilterInt(AFNFilter filter, const char* name, int value);
AFN_API void afnSetFilterFloat(AFNFilter filter, const char* name, float value);
AFN_API void afnSetFilterString(AFNFilter filter, const char* name, const char* value);
/// Set an array parameter: "viewProjection" (16 floats, row-vector convention clip = [p,1]·M, the
/// current frame's camera, as in the BMFR dataset's camera_matrices.h), "pixelOffset" (2 floats).
AFN_API void afnSetFilterFloats(AFNFilter filter, const char* name, const float* values,
                                size_t count);
/// Set an opaque data blob: "weights" (a weights archive; the library copies it).
AFN_API void afnSetFilterData(AFNFilter filter, const char* name, const void* data, size_t byteSize);

/// Read a parameter or a statistic of the last execute: "stats.nonFinite" (input values replaced
/// because NaN/Inf), "stats.negative" (negative colour values clamped), "frameIndex" (frames since
/// the last reset), "width", "height".
AFN_API bool afnGetFilterBool(AFNFilter filter, const char* name);
AFN_API int afnGetFilterInt(AFNFilter filter, const char* name);
AFN_API float afnGetFilterFloat(AFNFilter filter, const char* name);
/// The string is owned by the filter and valid until the parameter changes.
AFN_API const char* afnGetFilterString(AFNFilter filter, const char* name);

/// Register a progress callback (NULL to remove).
AFN_API void afnSetFilterProgressMonitorFunction(AFNFilter filter, AFNProgressMonitorFunction func,
                                                 void* userPtr);
/// Validate the bound images and parameters; errors name the offending input.
AFN_API void afnCommitFilter(AFNFilter filter);
/// Denoise one frame: read the inputs, write "output", advance the temporal history.
AFN_API void afnExecuteFilter(AFNFilter filter);
/// Drop the temporal history; the next execute behaves as the first frame of a sequence.
AFN_API void afnResetFilter(AFNFilter filter);

#ifdef __cplusplus
}
#endif

#endif // AFN_AFN_H
