// SPDX-License-Identifier: Apache-2.0
// The CPU device: thread count (a oneTBB arena) and the error state the C API reports.
#pragma once

#include "afn/afn.h"

#include <tbb/task_arena.h>

#include <functional>
#include <memory>
#include <mutex>
#include <string>

namespace afn {

class Device {
public:
    Device();
    ~Device();

    void setInt(const std::string& name, int value);
    int getInt(const std::string& name) const;
    void commit();
    bool committed() const { return m_committed; }

    /// Run fn inside this device's thread arena.
    template <typename Fn> void run(Fn&& fn);

    void setError(AFNError code, const std::string& message);
    AFNError takeError(const char** message);
    void setErrorFunction(AFNErrorFunction fn, void* user);

private:
    void runImpl(const std::function<void()>& fn);

    int m_numThreads = 0;
    int m_verbose = 0;
    bool m_committed = false;
    std::unique_ptr<tbb::task_arena> m_arena;

    std::mutex m_errorMutex;
    AFNError m_errorCode = AFN_ERROR_NONE;
    std::string m_errorMessage;
    std::string m_returnedMessage;
    AFNErrorFunction m_errorFn = nullptr;
    void* m_errorUser = nullptr;
};

template <typename Fn> void Device::run(Fn&& fn) { runImpl(std::function<void()>(std::forward<Fn>(fn))); }

} // namespace afn
