// SPDX-License-Identifier: Apache-2.0
// A device: its type, its thread count (a oneTBB arena) and the error state the C API reports.
// Concurrency (afn.h states the contract): executes hold the device's lock shared, so filters run
// concurrently; setInt() and commit() hold it exclusively, so the arena is never replaced while a
// filter runs on it. A CUDA device (builds with AFN_HAS_CUDA) finds its GPU when it is created;
// its filters still gather their inputs on the arena's threads, then run on the GPU.
#pragma once

#include "afn/afn.h"

#include <tbb/task_arena.h>

#include <functional>
#include <memory>
#include <mutex>
#include <shared_mutex>
#include <string>

namespace afn {

class Device {
public:
    /// Throws Unsupported for a type this build or machine cannot provide (the message says why:
    /// a build without CUDA, no driver, no GPU, a GPU too old for the build's kernels).
    explicit Device(AFNDeviceType type);
    ~Device();

    AFNDeviceType type() const { return m_type; }
    /// The CUDA device index of a CUDA device's GPU (-1 on the CPU device).
    int gpuOrdinal() const { return m_gpuOrdinal; }
    void setInt(const std::string& name, int value);
    int getInt(const std::string& name) const;
    void commit();
    bool committed() const;

    /// Run fn inside this device's thread arena (throws InvalidOperation when uncommitted).
    template <typename Fn> void run(Fn&& fn);

    void setError(AFNError code, const std::string& message);
    AFNError takeError(const char** message);
    void setErrorFunction(AFNErrorFunction fn, void* user);

private:
    void runImpl(const std::function<void()>& fn);

    AFNDeviceType m_type;
    int m_gpuOrdinal = -1;
    mutable std::shared_mutex m_stateMutex; ///< shared: executes; exclusive: settings and commit
    int m_numThreads = 0;
    bool m_committed = false;
    std::unique_ptr<tbb::task_arena> m_arena;

    std::mutex m_errorMutex;
    AFNError m_errorCode = AFN_ERROR_NONE;
    std::string m_errorMessage;
    std::string m_returnedMessage;
    AFNErrorFunction m_errorFn = nullptr;
    void* m_errorUser = nullptr;
};

template <typename Fn> void Device::run(Fn&& fn)
{
    runImpl(std::function<void()>(std::forward<Fn>(fn)));
}

} // namespace afn
