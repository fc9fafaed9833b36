// SPDX-License-Identifier: Apache-2.0
#include "base/device.h"

#include "base/exception.h"

#ifdef AFN_HAS_CUDA
#include "cuda/gpu.h"
#endif

#include <tbb/info.h>
#include <tbb/task_arena.h>

namespace afn {

Device::Device(AFNDeviceType type)
    : m_type(type == AFN_DEVICE_TYPE_DEFAULT ? AFN_DEVICE_TYPE_CPU : type)
{
    if (m_type == AFN_DEVICE_TYPE_CUDA) {
#ifdef AFN_HAS_CUDA
        m_gpuOrdinal = cuda::findGpu().ordinal;
        return;
#else
        throw Exception(AFN_ERROR_UNSUPPORTED,
            "this build of afn has no CUDA device (it was configured without a CUDA compiler; "
            "see docs/gpu.md)");
#endif
    }
    if (m_type != AFN_DEVICE_TYPE_CPU)
        throwInvalidArgument("unknown device type " + std::to_string(static_cast<int>(type)));
}

Device::~Device() = default;

void Device::setInt(const std::string& name, int value)
{
    std::unique_lock<std::shared_mutex> lock(m_stateMutex);
    if (name != "numThreads")
        throwInvalidArgument("unknown or read-only device parameter '" + name + "'");
    if (value < 0)
        throwInvalidArgument("numThreads must be >= 0 (0 = all cores)");
    m_numThreads = value;
    m_committed = false;
}

int Device::getInt(const std::string& name) const
{
    std::shared_lock<std::shared_mutex> lock(m_stateMutex);
    if (name == "numThreads")
        return m_numThreads;
    if (name == "type")
        return static_cast<int>(m_type);
    if (name == "version")
        return AFN_VERSION;
    throwInvalidArgument("unknown device parameter '" + name + "'");
}

void Device::commit()
{
    std::unique_lock<std::shared_mutex> lock(m_stateMutex);
    const int n = m_numThreads > 0 ? m_numThreads : tbb::info::default_concurrency();
    m_arena = std::make_unique<tbb::task_arena>(n);
    m_committed = true;
}

bool Device::committed() const
{
    std::shared_lock<std::shared_mutex> lock(m_stateMutex);
    return m_committed;
}

void Device::runImpl(const std::function<void()>& fn)
{
    std::shared_lock<std::shared_mutex> lock(m_stateMutex);
    if (!m_committed)
        throwInvalidOperation("device is not committed; call afnCommitDevice first");
    m_arena->execute(fn);
}

void Device::setError(AFNError code, const std::string& message)
{
    AFNErrorFunction fn = nullptr;
    void* user = nullptr;
    {
        std::lock_guard<std::mutex> lock(m_errorMutex);
        if (m_errorCode == AFN_ERROR_NONE) {
            m_errorCode = code;
            m_errorMessage = message;
        }
        fn = m_errorFn;
        user = m_errorUser;
    }
    if (fn)
        fn(user, code, message.c_str());
}

AFNError Device::takeError(const char** message)
{
    std::lock_guard<std::mutex> lock(m_errorMutex);
    const AFNError code = m_errorCode;
    m_returnedMessage = m_errorMessage;
    m_errorCode = AFN_ERROR_NONE;
    m_errorMessage.clear();
    if (message)
        *message = code == AFN_ERROR_NONE ? nullptr : m_returnedMessage.c_str();
    return code;
}

void Device::setErrorFunction(AFNErrorFunction fn, void* user)
{
    std::lock_guard<std::mutex> lock(m_errorMutex);
    m_errorFn = fn;
    m_errorUser = user;
}

} // namespace afn
