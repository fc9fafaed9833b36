// SPDX-License-Identifier: Apache-2.0
// Owners of CUDA resources: device buffers, a stream, an instantiated graph. Destructors release
// without throwing; allocation and creation failures throw (check.h).
#pragma once

#include "cuda/check.h"

#include <cuda_runtime_api.h>

#include <cstddef>
#include <utility>

namespace afn::cuda {

/// `count` elements of T in device memory.
template <typename T> class DeviceBuffer {
public:
    DeviceBuffer() = default;
    DeviceBuffer(const DeviceBuffer&) = delete;
    DeviceBuffer& operator=(const DeviceBuffer&) = delete;
    DeviceBuffer(DeviceBuffer&& o) noexcept
        : m_data(std::exchange(o.m_data, nullptr))
        , m_count(std::exchange(o.m_count, 0))
    {
    }
    DeviceBuffer& operator=(DeviceBuffer&& o) noexcept
    {
        if (this != &o) {
            release();
            m_data = std::exchange(o.m_data, nullptr);
            m_count = std::exchange(o.m_count, 0);
        }
        return *this;
    }
    ~DeviceBuffer() { release(); }

    /// Allocate `count` elements (contents undefined); keeps the memory when the count is equal.
    void resize(std::size_t count)
    {
        if (count == m_count)
            return;
        release();
        if (count == 0)
            return;
        void* p = nullptr;
        AFN_CUDA_CHECK(cudaMalloc(&p, count * sizeof(T)));
        m_data = static_cast<T*>(p);
        m_count = count;
    }
    void release()
    {
        if (m_data)
            cudaFree(m_data);
        m_data = nullptr;
        m_count = 0;
    }

    T* data() const { return m_data; }
    std::size_t size() const { return m_count; }
    std::size_t bytes() const { return m_count * sizeof(T); }

private:
    T* m_data = nullptr;
    std::size_t m_count = 0;
};

/// A non-blocking stream.
class Stream {
public:
    Stream() { AFN_CUDA_CHECK(cudaStreamCreateWithFlags(&m_stream, cudaStreamNonBlocking)); }
    Stream(const Stream&) = delete;
    Stream& operator=(const Stream&) = delete;
    ~Stream()
    {
        if (m_stream)
            cudaStreamDestroy(m_stream);
    }
    cudaStream_t get() const { return m_stream; }

private:
    cudaStream_t m_stream = nullptr;
};

/// An instantiated graph.
class GraphExec {
public:
    GraphExec() = default;
    GraphExec(const GraphExec&) = delete;
    GraphExec& operator=(const GraphExec&) = delete;
    ~GraphExec() { reset(); }
    void reset(cudaGraphExec_t exec = nullptr)
    {
        if (m_exec)
            cudaGraphExecDestroy(m_exec);
        m_exec = exec;
    }
    cudaGraphExec_t get() const { return m_exec; }
    explicit operator bool() const { return m_exec != nullptr; }

private:
    cudaGraphExec_t m_exec = nullptr;
};

/// Record into a graph everything `enqueue(stream)` puts on `stream`, and instantiate it. The
/// capture is ended (and the partial graph dropped) when `enqueue` throws.
template <typename Enqueue> cudaGraphExec_t captureGraph(cudaStream_t stream, Enqueue&& enqueue)
{
    AFN_CUDA_CHECK(cudaStreamBeginCapture(stream, cudaStreamCaptureModeThreadLocal));
    cudaGraph_t graph = nullptr;
    try {
        enqueue(stream);
    } catch (...) {
        if (cudaStreamEndCapture(stream, &graph) == cudaSuccess && graph)
            cudaGraphDestroy(graph);
        cudaGetLastError();
        throw;
    }
    AFN_CUDA_CHECK(cudaStreamEndCapture(stream, &graph));
    cudaGraphExec_t exec = nullptr;
    const cudaError_t error = cudaGraphInstantiate(&exec, graph, 0);
    cudaGraphDestroy(graph);
    checkCuda(error, "cudaGraphInstantiate", __FILE__, __LINE__);
    return exec;
}

} // namespace afn::cuda
