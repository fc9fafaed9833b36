// SPDX-License-Identifier: Apache-2.0
// The only implementation of the C ABI. Every entry point: check the handle, try, call the core,
// catch into the device's error state (or this thread's slot when there is no device).
#include "afn/afn.h"

#include "api_common.h"
#include "base/device.h"
#include "base/exception.h"
#include "filter/registry.h"

#include <atomic>
#include <cstring>
#include <new>
#include <string>

using namespace afn::api; // AFNDeviceImpl, kDeviceMagic, t_error, recordError, checkDevice

namespace {

constexpr std::uint32_t kFilterMagic = 0xAF4F1701u;

} // namespace

struct AFNFilterImpl {
    std::uint32_t magic = kFilterMagic;
    std::atomic<int> refs { 1 };
    AFNDeviceImpl* device = nullptr;
    std::unique_ptr<afn::Filter> filter;
    std::mutex mutex; ///< one call at a time per filter
    std::string stringResult;
};

namespace {

AFNFilterImpl* checkFilter(AFNFilter f)
{
    if (!f || f->magic != kFilterMagic)
        afn::throwInvalidArgument("invalid filter handle");
    return f;
}

std::string checkName(const char* name)
{
    if (!name)
        afn::throwInvalidArgument("null name");
    return name;
}

/// The filter type named `type`, or null (also for a null name).
const afn::FilterType* typeOf(const char* type)
{
    return type ? afn::findFilterType(type) : nullptr;
}

AFNDeviceImpl* deviceOf(AFNFilter f)
{
    return (f && f->magic == kFilterMagic) ? f->device : nullptr;
}

} // namespace

extern "C" {

// ---- Device -------------------------------------------------------------------------------------

AFN_API AFNDevice afnNewDevice(AFNDeviceType type)
{
    AFN_TRY
    // A C caller may pass any int; an enum value outside the enumerators is undefined behaviour
    // once C++ loads it (UBSan: "not a valid value for type 'AFNDeviceType'"), so check the bytes.
    static_assert(sizeof(type) == sizeof(int), "AFNDeviceType is passed as an int");
    int raw = 0;
    std::memcpy(&raw, &type, sizeof raw);
    if (raw != AFN_DEVICE_TYPE_DEFAULT && raw != AFN_DEVICE_TYPE_CPU && raw != AFN_DEVICE_TYPE_CUDA)
        afn::throwInvalidArgument("unknown device type " + std::to_string(raw));
    return new AFNDeviceImpl(type);
    AFN_CATCH(nullptr)
    return nullptr;
}

AFN_API void afnRetainDevice(AFNDevice d)
{
    AFN_TRY
    checkDevice(d)->refs++;
    AFN_CATCH(nullptr)
}

AFN_API void afnReleaseDevice(AFNDevice d)
{
    AFN_TRY
    if (--checkDevice(d)->refs == 0) {
        d->magic = 0;
        delete d;
    }
    AFN_CATCH(nullptr)
}

AFN_API void afnSetDeviceInt(AFNDevice d, const char* name, int value)
{
    AFN_TRY
    checkDevice(d)->device.setInt(checkName(name), value);
    AFN_CATCH(d)
}

AFN_API int afnGetDeviceInt(AFNDevice d, const char* name)
{
    AFN_TRY
    return checkDevice(d)->device.getInt(checkName(name));
    AFN_CATCH(d)
    return 0;
}

AFN_API void afnSetDeviceErrorFunction(AFNDevice d, AFNErrorFunction func, void* userPtr)
{
    AFN_TRY
    checkDevice(d)->device.setErrorFunction(func, userPtr);
    AFN_CATCH(d)
}

AFN_API void afnCommitDevice(AFNDevice d)
{
    AFN_TRY
    checkDevice(d)->device.commit();
    AFN_CATCH(d)
}

AFN_API AFNError afnGetDeviceError(AFNDevice d, const char** outMessage)
{
    if (d && d->magic == kDeviceMagic)
        return d->device.takeError(outMessage);
    const AFNError code = t_error.code;
    t_error.returned = t_error.message;
    t_error.code = AFN_ERROR_NONE;
    t_error.message.clear();
    if (outMessage)
        *outMessage = code == AFN_ERROR_NONE ? nullptr : t_error.returned.c_str();
    return code;
}

// ---- Filter types -------------------------------------------------------------------------------

AFN_API int afnGetNumFilterTypes(void)
{
    return static_cast<int>(afn::filterTypes().size());
}

AFN_API const char* afnGetFilterTypeName(int index)
{
    const auto& types = afn::filterTypes();
    if (index < 0 || index >= static_cast<int>(types.size()))
        return nullptr;
    return types[index].name.c_str();
}

AFN_API const char* afnGetFilterTypeDescription(const char* type)
{
    const afn::FilterType* t = typeOf(type);
    return t ? t->description.c_str() : nullptr;
}

AFN_API bool afnIsFilterTypeReady(const char* type)
{
    const afn::FilterType* t = typeOf(type);
    return t && t->ready;
}

AFN_API int afnGetFilterTypeNumFeatures(const char* type)
{
    const afn::FilterType* t = typeOf(type);
    return t ? static_cast<int>(t->features.size()) : -1;
}

AFN_API bool afnGetFilterTypeFeature(const char* type, int index, AFNFeatureInfo* info)
{
    const afn::FilterType* t = typeOf(type);
    if (!t || !info || index < 0 || index >= static_cast<int>(t->features.size()))
        return false;
    const afn::FeatureOutput& f = t->features[index];
    info->name = f.name.c_str();
    info->channels = f.channels;
    info->help = f.help.c_str();
    return true;
}

AFN_API int afnGetFilterTypeNumParams(const char* type)
{
    const afn::FilterType* t = typeOf(type);
    return t ? static_cast<int>(t->params.size()) : -1;
}

AFN_API bool afnGetFilterTypeParam(const char* type, int index, AFNParamInfo* info)
{
    const afn::FilterType* t = typeOf(type);
    if (!t || !info || index < 0 || index >= static_cast<int>(t->params.size()))
        return false;
    const afn::ParamDesc& d = t->params[index];
    info->name = d.name.c_str();
    info->type = d.type;
    info->defaultValue = d.defaultValue;
    info->minValue = d.minValue;
    info->maxValue = d.maxValue;
    info->defaultString = d.defaultString.c_str();
    info->choices = d.choices.c_str();
    info->label = d.label.c_str();
    info->help = d.help.c_str();
    return true;
}

// ---- Filter -------------------------------------------------------------------------------------

AFN_API AFNFilter afnNewFilter(AFNDevice d, const char* type)
{
    AFN_TRY
    checkDevice(d);
    if (!d->device.committed())
        afn::throwInvalidOperation("device is not committed");
    auto impl = std::make_unique<AFNFilterImpl>();
    impl->filter = afn::createFilter(checkName(type), d->device);
    impl->device = d;
    d->refs++;
    return impl.release();
    AFN_CATCH(d)
    return nullptr;
}

AFN_API void afnRetainFilter(AFNFilter f)
{
    AFN_TRY
    checkFilter(f)->refs++;
    AFN_CATCH(deviceOf(f))
}

AFN_API void afnReleaseFilter(AFNFilter f)
{
    AFN_TRY
    if (--checkFilter(f)->refs == 0) {
        AFNDeviceImpl* d = f->device;
        f->magic = 0;
        delete f;
        afnReleaseDevice(d);
    }
    AFN_CATCH(deviceOf(f))
}

AFN_API void afnSetFilterImage(AFNFilter f, const char* name, void* ptr, AFNFormat format,
    size_t width, size_t height, size_t byteOffset, size_t pixelByteStride, ptrdiff_t rowByteStride)
{
    AFN_TRY
    checkFilter(f);
    std::lock_guard<std::mutex> lock(f->mutex);
    if (width > (1u << 16) || height > (1u << 16))
        afn::throwInvalidArgument("image larger than 65536 pixels on a side");
    afn::ImageBinding b;
    b.ptr = ptr;
    b.format = format;
    b.width = static_cast<int>(width);
    b.height = static_cast<int>(height);
    b.byteOffset = byteOffset;
    const std::size_t ch = (format >= AFN_FORMAT_FLOAT && format <= AFN_FORMAT_FLOAT4) ? format : 1;
    b.pixelStride = pixelByteStride ? static_cast<std::ptrdiff_t>(pixelByteStride)
                                    : static_cast<std::ptrdiff_t>(ch * sizeof(float));
    b.rowStride
        = rowByteStride ? rowByteStride : b.pixelStride * static_cast<std::ptrdiff_t>(width);
    f->filter->setImage(checkName(name), b);
    AFN_CATCH(deviceOf(f))
}

AFN_API void afnUnsetFilterImage(AFNFilter f, const char* name)
{
    AFN_TRY
    checkFilter(f);
    std::lock_guard<std::mutex> lock(f->mutex);
    f->filter->unsetImage(checkName(name));
    AFN_CATCH(deviceOf(f))
}

#define AFN_SET_NUMBER(FN, T, PT)                                                                  \
    AFN_API void FN(AFNFilter f, const char* name, T value)                                        \
    {                                                                                              \
        AFN_TRY                                                                                    \
        checkFilter(f);                                                                            \
        std::lock_guard<std::mutex> lock(f->mutex);                                                \
        f->filter->params().setNumber(checkName(name), static_cast<double>(value), PT);            \
        f->filter->markDirty();                                                                    \
        AFN_CATCH(deviceOf(f))                                                                     \
    }

AFN_SET_NUMBER(afnSetFilterBool, bool, AFN_PARAM_BOOL)
AFN_SET_NUMBER(afnSetFilterInt, int, AFN_PARAM_INT)
AFN_SET_NUMBER(afnSetFilterFloat, float, AFN_PARAM_FLOAT)

AFN_API void afnSetFilterString(AFNFilter f, const char* name, const char* value)
{
    AFN_TRY
    checkFilter(f);
    std::lock_guard<std::mutex> lock(f->mutex);
    if (!value)
        afn::throwInvalidArgument("null string value");
    f->filter->params().setString(checkName(name), value);
    f->filter->markDirty();
    AFN_CATCH(deviceOf(f))
}

AFN_API void afnSetFilterFloats(AFNFilter f, const char* name, const float* values, size_t count)
{
    AFN_TRY
    checkFilter(f);
    std::lock_guard<std::mutex> lock(f->mutex);
    if (!values && count)
        afn::throwInvalidArgument("null values");
    f->filter->setFloats(checkName(name), std::vector<float>(values, values + count));
    AFN_CATCH(deviceOf(f))
}

AFN_API void afnSetFilterData(AFNFilter f, const char* name, const void* data, size_t byteSize)
{
    AFN_TRY
    checkFilter(f);
    std::lock_guard<std::mutex> lock(f->mutex);
    if (!data && byteSize)
        afn::throwInvalidArgument("null data");
    f->filter->setData(checkName(name), data, byteSize);
    f->filter->markDirty();
    AFN_CATCH(deviceOf(f))
}

/// The aux report of the last frame; a clean history's speckle shares are measured when first
/// asked for (Filter::auxReport), in the device's thread arena as an execute is.
static const afn::AuxReport& auxReportOf(AFNFilterImpl* f)
{
    const afn::AuxReport* report = nullptr;
    f->device->device.run([&] { report = &f->filter->auxReport(); });
    return *report;
}

static double filterNumber(AFNFilterImpl* f, const std::string& name)
{
    afn::Filter& flt = *f->filter;
    if (name == "stats.nonFinite")
        return static_cast<double>(flt.lastStats().nonFinite);
    if (name == "stats.negative")
        return static_cast<double>(flt.lastStats().negative);
    if (name == "frameIndex")
        return flt.frameIndex();
    if (name == "width")
        return flt.width();
    if (name == "height")
        return flt.height();
    if (name == AFN_STAT_SKIPPED)
        return flt.lastSkippedShare();
    if (name == AFN_STAT_HISTORY_CUT)
        return flt.lastHistoryCutShare();
    if (name == AFN_STAT_RESTORED)
        return flt.lastRestoredShare();
    if (name == AFN_STAT_HIGHLIGHTS)
        return static_cast<double>(flt.lastHighlightPixels());
    if (name == AFN_STAT_AUX_NOISY)
        return flt.auxNoisy() ? 1.0 : 0.0;
    if (name == AFN_STAT_AUX_GRAIN_LIMITED)
        return flt.auxGrainLimited() ? 1.0 : 0.0;
    if (name == AFN_STAT_ALBEDO_SPECKLE)
        return auxReportOf(f).albedoSpeckle;
    if (name == AFN_STAT_NORMAL_SPECKLE)
        return auxReportOf(f).normalSpeckle;
    if (name == AFN_STAT_DEPTH_SPECKLE)
        return auxReportOf(f).depthSpeckle;
    double value = 0.0;
    if (flt.statistic(name, value))
        return value;
    return flt.params().getNumber(name);
}

AFN_API bool afnGetFilterBool(AFNFilter f, const char* name)
{
    AFN_TRY
    checkFilter(f);
    std::lock_guard<std::mutex> lock(f->mutex);
    return filterNumber(f, checkName(name)) != 0.0;
    AFN_CATCH(deviceOf(f))
    return false;
}

AFN_API int afnGetFilterInt(AFNFilter f, const char* name)
{
    AFN_TRY
    checkFilter(f);
    std::lock_guard<std::mutex> lock(f->mutex);
    return static_cast<int>(filterNumber(f, checkName(name)));
    AFN_CATCH(deviceOf(f))
    return 0;
}

AFN_API float afnGetFilterFloat(AFNFilter f, const char* name)
{
    AFN_TRY
    checkFilter(f);
    std::lock_guard<std::mutex> lock(f->mutex);
    return static_cast<float>(filterNumber(f, checkName(name)));
    AFN_CATCH(deviceOf(f))
    return 0.0f;
}

AFN_API const char* afnGetFilterString(AFNFilter f, const char* name)
{
    AFN_TRY
    checkFilter(f);
    std::lock_guard<std::mutex> lock(f->mutex);
    const std::string key = checkName(name);
    if (key == AFN_STAT_MISSING_INPUTS)
        f->stringResult = f->filter->lastMissingInputs();
    else if (!f->filter->stringStatistic(key, f->stringResult))
        f->stringResult = f->filter->params().getString(key);
    return f->stringResult.c_str();
    AFN_CATCH(deviceOf(f))
    return nullptr;
}

AFN_API void afnSetFilterProgressMonitorFunction(
    AFNFilter f, AFNProgressMonitorFunction func, void* userPtr)
{
    AFN_TRY
    checkFilter(f);
    std::lock_guard<std::mutex> lock(f->mutex);
    if (func)
        f->filter->setProgressMonitor([func, userPtr](double p) { return func(userPtr, p); });
    else
        f->filter->setProgressMonitor(nullptr);
    AFN_CATCH(deviceOf(f))
}

AFN_API void afnCommitFilter(AFNFilter f)
{
    AFN_TRY
    checkFilter(f);
    std::lock_guard<std::mutex> lock(f->mutex);
    f->filter->commit();
    AFN_CATCH(deviceOf(f))
}

AFN_API void afnExecuteFilter(AFNFilter f)
{
    AFN_TRY
    checkFilter(f);
    std::lock_guard<std::mutex> lock(f->mutex);
    f->device->device.run([&] { f->filter->execute(); });
    AFN_CATCH(deviceOf(f))
}

AFN_API void afnResetFilter(AFNFilter f)
{
    AFN_TRY
    checkFilter(f);
    std::lock_guard<std::mutex> lock(f->mutex);
    f->filter->reset();
    AFN_CATCH(deviceOf(f))
}

} // extern "C"
