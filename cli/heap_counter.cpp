// SPDX-License-Identifier: Apache-2.0
// Replacement of the global operator new/delete that counts live and peak heap bytes (see
// heap_counter.h). Exported with default visibility so that the shared libraries' calls reach it.
#include "heap_counter.h"

#include <atomic>
#include <cstdlib>
#include <malloc.h>
#include <new>

namespace afntool::heap {

namespace {

std::atomic<std::size_t> g_live { 0 }, g_peak { 0 };

void* allocate(std::size_t n, std::size_t align)
{
    void* p = nullptr;
    if (align <= alignof(std::max_align_t))
        p = std::malloc(n ? n : 1);
    else if (posix_memalign(&p, align, n ? n : 1) != 0)
        p = nullptr;
    if (!p)
        throw std::bad_alloc();
    const std::size_t live = g_live.fetch_add(malloc_usable_size(p)) + malloc_usable_size(p);
    std::size_t peak = g_peak.load(std::memory_order_relaxed);
    while (live > peak && !g_peak.compare_exchange_weak(peak, live))
        ;
    return p;
}

void release(void* p)
{
    if (!p)
        return;
    g_live.fetch_sub(malloc_usable_size(p));
    std::free(p);
}

} // namespace

std::size_t liveBytes()
{
    return g_live.load();
}

std::size_t peakBytes()
{
    return g_peak.load();
}

void resetPeak()
{
    g_peak.store(g_live.load());
}

} // namespace afntool::heap

#define AFN_HEAP_EXPORT __attribute__((visibility("default")))

AFN_HEAP_EXPORT void* operator new(std::size_t n)
{
    return afntool::heap::allocate(n, 0);
}
AFN_HEAP_EXPORT void* operator new[](std::size_t n)
{
    return afntool::heap::allocate(n, 0);
}
AFN_HEAP_EXPORT void* operator new(std::size_t n, std::align_val_t a)
{
    return afntool::heap::allocate(n, static_cast<std::size_t>(a));
}
AFN_HEAP_EXPORT void* operator new[](std::size_t n, std::align_val_t a)
{
    return afntool::heap::allocate(n, static_cast<std::size_t>(a));
}
AFN_HEAP_EXPORT void* operator new(std::size_t n, const std::nothrow_t&) noexcept
{
    try {
        return afntool::heap::allocate(n, 0);
    } catch (...) {
        return nullptr;
    }
}
AFN_HEAP_EXPORT void* operator new[](std::size_t n, const std::nothrow_t&) noexcept
{
    try {
        return afntool::heap::allocate(n, 0);
    } catch (...) {
        return nullptr;
    }
}
AFN_HEAP_EXPORT void operator delete(void* p) noexcept
{
    afntool::heap::release(p);
}
AFN_HEAP_EXPORT void operator delete[](void* p) noexcept
{
    afntool::heap::release(p);
}
AFN_HEAP_EXPORT void operator delete(void* p, std::size_t) noexcept
{
    afntool::heap::release(p);
}
AFN_HEAP_EXPORT void operator delete[](void* p, std::size_t) noexcept
{
    afntool::heap::release(p);
}
AFN_HEAP_EXPORT void operator delete(void* p, std::align_val_t) noexcept
{
    afntool::heap::release(p);
}
AFN_HEAP_EXPORT void operator delete[](void* p, std::align_val_t) noexcept
{
    afntool::heap::release(p);
}
AFN_HEAP_EXPORT void operator delete(void* p, std::size_t, std::align_val_t) noexcept
{
    afntool::heap::release(p);
}
AFN_HEAP_EXPORT void operator delete[](void* p, std::size_t, std::align_val_t) noexcept
{
    afntool::heap::release(p);
}
