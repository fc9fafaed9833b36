// SPDX-License-Identifier: Apache-2.0
// afn header-only C++ wrapper: reference-counted handles over the C API. It never throws on its
// own; errors are read with DeviceRef::getError(), exactly as with the C API.
#pragma once

#include "afn/afn.h"

#include <fstream>
#include <iterator>
#include <string>
#include <utility>
#include <vector>

namespace afn {

/// Error codes as an enum class.
enum class Error {
    None = AFN_ERROR_NONE,
    Unknown = AFN_ERROR_UNKNOWN,
    InvalidArgument = AFN_ERROR_INVALID_ARGUMENT,
    InvalidOperation = AFN_ERROR_INVALID_OPERATION,
    OutOfMemory = AFN_ERROR_OUT_OF_MEMORY,
    Unsupported = AFN_ERROR_UNSUPPORTED,
    Cancelled = AFN_ERROR_CANCELLED,
};

/// Device types as an enum class.
enum class DeviceType {
    Default = AFN_DEVICE_TYPE_DEFAULT,
    CPU = AFN_DEVICE_TYPE_CPU,
    CUDA = AFN_DEVICE_TYPE_CUDA,
};

/// Pixel formats as an enum class.
enum class Format {
    Undefined = AFN_FORMAT_UNDEFINED,
    Float = AFN_FORMAT_FLOAT,
    Float2 = AFN_FORMAT_FLOAT2,
    Float3 = AFN_FORMAT_FLOAT3,
    Float4 = AFN_FORMAT_FLOAT4,
};

/// Reference to a filter: copy = retain, move = steal.
class FilterRef {
public:
    FilterRef() = default;
    explicit FilterRef(AFNFilter handle)
        : m_handle(handle)
    {
    }
    FilterRef(const FilterRef& o)
        : m_handle(o.m_handle)
    {
        if (m_handle)
            afnRetainFilter(m_handle);
    }
    FilterRef(FilterRef&& o) noexcept
        : m_handle(std::exchange(o.m_handle, nullptr))
    {
    }
    FilterRef& operator=(const FilterRef& o)
    {
        if (o.m_handle)
            afnRetainFilter(o.m_handle);
        if (m_handle)
            afnReleaseFilter(m_handle);
        m_handle = o.m_handle;
        return *this;
    }
    FilterRef& operator=(FilterRef&& o) noexcept
    {
        std::swap(m_handle, o.m_handle);
        return *this;
    }
    ~FilterRef()
    {
        if (m_handle)
            afnReleaseFilter(m_handle);
    }

    AFNFilter getHandle() const { return m_handle; }
    explicit operator bool() const { return m_handle != nullptr; }

    /// Bind a strided float image (strides in bytes, 0 = packed; row stride may be negative).
    void setImage(const char* name, void* ptr, Format format, size_t width, size_t height,
        size_t byteOffset = 0, size_t pixelByteStride = 0, ptrdiff_t rowByteStride = 0)
    {
        afnSetFilterImage(m_handle, name, ptr, static_cast<AFNFormat>(format), width, height,
            byteOffset, pixelByteStride, rowByteStride);
    }
    void unsetImage(const char* name) { afnUnsetFilterImage(m_handle, name); }

    void set(const char* name, bool v) { afnSetFilterBool(m_handle, name, v); }
    void set(const char* name, int v) { afnSetFilterInt(m_handle, name, v); }
    void set(const char* name, float v) { afnSetFilterFloat(m_handle, name, v); }
    void set(const char* name, double v)
    {
        afnSetFilterFloat(m_handle, name, static_cast<float>(v));
    }
    void set(const char* name, const char* v) { afnSetFilterString(m_handle, name, v); }
    void set(const char* name, const std::string& v)
    {
        afnSetFilterString(m_handle, name, v.c_str());
    }
    void setFloats(const char* name, const float* v, size_t n)
    {
        afnSetFilterFloats(m_handle, name, v, n);
    }
    void setData(const char* name, const void* p, size_t n)
    {
        afnSetFilterData(m_handle, name, p, n);
    }

    /// Typed getter: get<int>("stats.nonFinite"), get<std::string>("normal.space").
    template <typename T> T get(const char* name) const;

    void setProgressMonitorFunction(AFNProgressMonitorFunction f, void* user = nullptr)
    {
        afnSetFilterProgressMonitorFunction(m_handle, f, user);
    }
    void commit() { afnCommitFilter(m_handle); }
    void execute() { afnExecuteFilter(m_handle); }
    void reset() { afnResetFilter(m_handle); }

private:
    AFNFilter m_handle = nullptr;
};

template <> inline bool FilterRef::get<bool>(const char* n) const
{
    return afnGetFilterBool(m_handle, n);
}
template <> inline int FilterRef::get<int>(const char* n) const
{
    return afnGetFilterInt(m_handle, n);
}
template <> inline float FilterRef::get<float>(const char* n) const
{
    return afnGetFilterFloat(m_handle, n);
}
template <> inline std::string FilterRef::get<std::string>(const char* n) const
{
    const char* s = afnGetFilterString(m_handle, n);
    return s ? std::string(s) : std::string();
}

/// Reference to a device: copy = retain, move = steal.
class DeviceRef {
public:
    DeviceRef() = default;
    explicit DeviceRef(AFNDevice handle)
        : m_handle(handle)
    {
    }
    DeviceRef(const DeviceRef& o)
        : m_handle(o.m_handle)
    {
        if (m_handle)
            afnRetainDevice(m_handle);
    }
    DeviceRef(DeviceRef&& o) noexcept
        : m_handle(std::exchange(o.m_handle, nullptr))
    {
    }
    DeviceRef& operator=(const DeviceRef& o)
    {
        if (o.m_handle)
            afnRetainDevice(o.m_handle);
        if (m_handle)
            afnReleaseDevice(m_handle);
        m_handle = o.m_handle;
        return *this;
    }
    DeviceRef& operator=(DeviceRef&& o) noexcept
    {
        std::swap(m_handle, o.m_handle);
        return *this;
    }
    ~DeviceRef()
    {
        if (m_handle)
            afnReleaseDevice(m_handle);
    }

    AFNDevice getHandle() const { return m_handle; }
    explicit operator bool() const { return m_handle != nullptr; }

    void set(const char* name, int v) { afnSetDeviceInt(m_handle, name, v); }
    int get(const char* name) const { return afnGetDeviceInt(m_handle, name); }
    void setErrorFunction(AFNErrorFunction f, void* user = nullptr)
    {
        afnSetDeviceErrorFunction(m_handle, f, user);
    }
    void commit() { afnCommitDevice(m_handle); }

    /// Return and clear the first unqueried error; the message is copied.
    Error getError(std::string* message = nullptr)
    {
        const char* msg = nullptr;
        const Error e = static_cast<Error>(afnGetDeviceError(m_handle, &msg));
        if (message)
            *message = msg ? msg : "";
        return e;
    }

    FilterRef newFilter(const char* type) { return FilterRef(afnNewFilter(m_handle, type)); }

private:
    AFNDevice m_handle = nullptr;
};

/// Create a device (NULL handle on failure: read the error with afnGetDeviceError(NULL, ...)).
inline DeviceRef newDevice(DeviceType type = DeviceType::Default)
{
    return DeviceRef(afnNewDevice(static_cast<AFNDeviceType>(type)));
}

/// Feature outputs of a filter type.
inline std::vector<AFNFeatureInfo> filterTypeFeatures(const char* type)
{
    std::vector<AFNFeatureInfo> out;
    const int n = afnGetFilterTypeNumFeatures(type);
    for (int i = 0; i < n; ++i) {
        AFNFeatureInfo info {};
        if (afnGetFilterTypeFeature(type, i, &info))
            out.push_back(info);
    }
    return out;
}

/// Split a '|'-separated choice list (AFNParamInfo::choices).
inline std::vector<std::string> splitChoices(const char* choices)
{
    std::vector<std::string> out;
    std::string item;
    for (const char* c = choices ? choices : "";; ++c) {
        if (*c == '|' || *c == '\0') {
            if (!item.empty())
                out.push_back(item);
            item.clear();
            if (*c == '\0')
                break;
        } else {
            item += *c;
        }
    }
    return out;
}

/// True when filters of this type run as created (see afnIsFilterTypeReady).
inline bool isFilterTypeReady(const char* type)
{
    return afnIsFilterTypeReady(type);
}

/// Read a whole file (a weights archive for AFN_DATA_WEIGHTS) into `bytes`; false if it cannot be
/// read. The library never reads files itself; this helper runs in the caller's code.
inline bool readFile(const std::string& path, std::vector<char>& bytes)
{
    std::ifstream in(path, std::ios::binary);
    if (!in)
        return false;
    bytes.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    return !in.bad();
}

/// Names of every filter type of this build.
inline std::vector<std::string> filterTypes()
{
    std::vector<std::string> out;
    for (int i = 0, n = afnGetNumFilterTypes(); i < n; ++i)
        out.emplace_back(afnGetFilterTypeName(i));
    return out;
}

/// Parameters of a filter type.
inline std::vector<AFNParamInfo> filterTypeParams(const char* type)
{
    std::vector<AFNParamInfo> out;
    const int n = afnGetFilterTypeNumParams(type);
    for (int i = 0; i < n; ++i) {
        AFNParamInfo info {};
        if (afnGetFilterTypeParam(type, i, &info))
            out.push_back(info);
    }
    return out;
}

// ---- Image-quality metrics (conventions: afn.h and docs/metrics.md) ----------------------------

/// Metrics of `test` against `reference` (packed rows of width * pixelFloatStride floats).
/// Returns false on error (read it with device.getError()); `out` is then unchanged.
inline bool computeMetrics(const DeviceRef& device, const float* test, const float* reference,
    size_t width, size_t height, size_t pixelFloatStride, AFNMetrics& out)
{
    return afnComputeMetrics(
        device.getHandle(), test, reference, width, height, pixelFloatStride, &out);
}

/// Temporal-gradient error of (testPrev, test) against (referencePrev, reference).
inline bool computeTemporalMetrics(const DeviceRef& device, const float* testPrev,
    const float* test, const float* referencePrev, const float* reference, size_t width,
    size_t height, size_t pixelFloatStride, AFNTemporalMetrics& out)
{
    return afnComputeTemporalMetrics(device.getHandle(), testPrev, test, referencePrev, reference,
        width, height, pixelFloatStride, &out);
}

} // namespace afn
