// SPDX-License-Identifier: Apache-2.0
// Shared pieces of the C ABI implementation (api.cpp, api_metrics.cpp): the device handle, the
// per-thread error slot and the try/catch macros that turn exceptions into recorded errors.
#pragma once

#include "afn/afn.h"

#include "base/device.h"
#include "base/exception.h"

#include <atomic>
#include <cstdint>
#include <new>
#include <string>

namespace afn::api {

constexpr std::uint32_t kDeviceMagic = 0xAF4D0E01u;

/// Error slot for calls made without a valid device.
struct ThreadError {
    AFNError code = AFN_ERROR_NONE;
    std::string message;
    std::string returned;
};
inline thread_local ThreadError t_error;

} // namespace afn::api

struct AFNDeviceImpl {
    explicit AFNDeviceImpl(AFNDeviceType type)
        : device(type)
    {
    }
    std::uint32_t magic = afn::api::kDeviceMagic;
    std::atomic<int> refs { 1 };
    afn::Device device;
};

namespace afn::api {

/// Record an error on the device, or in this thread's slot when the device is not valid.
inline void recordError(AFNDeviceImpl* d, AFNError code, const std::string& msg)
{
    if (d && d->magic == kDeviceMagic) {
        d->device.setError(code, msg);
    } else if (t_error.code == AFN_ERROR_NONE) {
        t_error.code = code;
        t_error.message = msg;
    }
}

/// The device behind a handle; throws (invalid argument) for NULL or a stale handle.
inline AFNDeviceImpl* checkDevice(AFNDevice d)
{
    if (!d || d->magic != kDeviceMagic)
        afn::throwInvalidArgument("invalid device handle");
    return d;
}

} // namespace afn::api

#define AFN_TRY try {
#define AFN_CATCH(dev)                                                                             \
    }                                                                                              \
    catch (const afn::Exception& e)                                                                \
    {                                                                                              \
        afn::api::recordError(dev, e.code(), e.what());                                            \
    }                                                                                              \
    catch (const std::bad_alloc&)                                                                  \
    {                                                                                              \
        afn::api::recordError(dev, AFN_ERROR_OUT_OF_MEMORY, "out of memory");                      \
    }                                                                                              \
    catch (const std::exception& e)                                                                \
    {                                                                                              \
        afn::api::recordError(dev, AFN_ERROR_UNKNOWN, e.what());                                   \
    }                                                                                              \
    catch (...)                                                                                    \
    {                                                                                              \
        afn::api::recordError(dev, AFN_ERROR_UNKNOWN, "unknown error");                            \
    }
