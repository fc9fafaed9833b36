// SPDX-License-Identifier: Apache-2.0
#include "base/device.h"

#include "base/exception.h"

#include <tbb/info.h>
#include <tbb/task_arena.h>

namespace afn {

Device::Device() = default;
Device::~Device() = default;

void Device::setInt(const std::string& name, int value)
{
    if (name == "numThreads") {
        if (value < 0) throwInvalidArgument("numThreads must be >= 0 (0 = all cores)");
        m_numThreads = value;
    } else if (name == "verbose") {
        m_verbose = value;
    } else {
        throwInvalidArgument("unknown device parameter '" + name + "'");
    }
    m_committed = false;
}

int Device::getInt(const std::string& name) const
{
    if (name == "numThreads") return m_numThreads;
    if (name == "verbose") return m_verbose;
    if (name == "version") return AFN_VERSION;
    throwInvalidArgument("unknown device parameter '" + name + "'");
}

void Device::commit()
{
    const int n = m_numThreads > 0 ? m_numThreads : tbb::info::default_concurrency();
    m_arena = std::make_unique<tbb::task_arena>(n);
    m_committed = true;
}

void Device::runImpl(const std::function<void()>& fn)
{
    if (!m_committed) throwInvalidOperation("device is not committed; call afnCommitDevice first");
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
    if (fn) fn(user, code, message.c_str());
}

AFNError Device::takeError(const char** message)
{
    std::lock_guard<std::mutex> lock(m_errorMutex);
    const AFNError code = m_errorCode;
    m_returnedMessage = m_errorMessage;
    m_errorCode = AFN_ERROR_NONE;
    m_errorMessage.clear();
    if (message) *message = code == AFN_ERROR_NONE ? nullptr : m_returnedMessage.c_str();
    return code;
}

void Device::setErrorFunction(AFNErrorFunction fn, void* user)
{
    std::lock_guard<std::mutex> lock(m_errorMutex);
    m_errorFn = fn;
    m_errorUser = user;
}

} // namespace afn
