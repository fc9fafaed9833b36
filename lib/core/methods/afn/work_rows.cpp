// SPDX-License-Identifier: Apache-2.0
// Rows under work skipping (see methods/afn/work_rows.h).
#include "methods/afn/work_rows.h"

#include "methods/afn/post_filter.h"
#include "stages/taa.h"

#include <algorithm>

namespace afn::afnet {

void growWorkRows(const Image& work, int margin, Image& dst)
{
    if (work.empty()) {
        dst = Image {};
        return;
    }
    const int w = work.width(), h = work.height();
    std::vector<char> any(static_cast<std::size_t>(h), 0);
    for (int y = 0; y < h; ++y)
        any[y] = std::any_of(work.at(0, y), work.at(0, y) + w, [](float v) { return v > 0.0f; });
    dst.resize(w, h, 1);
    for (int y = 0; y < h; ++y) {
        bool near = false;
        for (int k = std::max(0, y - margin); k <= std::min(h - 1, y + margin) && !near; ++k)
            near = any[k] != 0;
        std::fill(dst.at(0, y), dst.at(0, y) + w, near ? 1.0f : 0.0f);
    }
}

std::vector<char> computedRows(const Image* work, int h)
{
    std::vector<char> computed(static_cast<std::size_t>(std::max(h, 0)), 1);
    if (!work || work->empty())
        return computed;
    const int w = work->width();
    for (int y0 = 0; y0 < h; y0 += 8) {
        const int y1 = std::min(h, y0 + 8);
        const float* m = work->at(0, y0);
        const bool needed = std::any_of(
            m, m + static_cast<std::size_t>(y1 - y0) * w, [](float v) { return v != 0.0f; });
        std::fill(computed.begin() + y0, computed.begin() + y1, needed ? 1 : 0);
    }
    return computed;
}

int workMargin(bool taa, bool postFilter)
{
    return (taa ? kTaaWorkMargin : 0) + (postFilter ? kPostFilterRadius : 0);
}

std::vector<char> computedRows(const Image& work, int margin, int h, Image& grown)
{
    if (margin <= 0 || work.empty())
        return computedRows(&work, h);
    growWorkRows(work, margin, grown);
    return computedRows(&grown, h);
}

} // namespace afn::afnet
