// SPDX-License-Identifier: Apache-2.0
// Pooling and activation helpers (see nn/pool.h).
#include "nn/pool.h"

#include "base/exception.h"
#include "base/parallel.h"

#include <algorithm>

namespace afn::nn {

void maxPool2(const Image& in, Image& out)
{
    const int w = in.width() / 2, h = in.height() / 2, c = in.channels();
    out.resize(w, h, c);
    parallelRows(h, [&](int y0, int y1) {
        for (int y = y0; y < y1; ++y)
            for (int x = 0; x < w; ++x) {
                const float* a = in.at(2 * x, 2 * y);
                const float* b = in.at(2 * x + 1, 2 * y);
                const float* cc = in.at(2 * x, 2 * y + 1);
                const float* d = in.at(2 * x + 1, 2 * y + 1);
                float* o = out.at(x, y);
                for (int k = 0; k < c; ++k)
                    o[k] = std::max(std::max(a[k], b[k]), std::max(cc[k], d[k]));
            }
    });
}

void leakyRelu(Image& img, float slope)
{
    float* p = img.data();
    const long n = static_cast<long>(img.size());
    const int rows = img.height();
    const long perRow = rows > 0 ? n / rows : 0;
    parallelRows(rows, [&](int y0, int y1) {
        for (long k = y0 * perRow; k < y1 * perRow; ++k)
            p[k] = p[k] > 0.0f ? p[k] : slope * p[k];
    });
}

void copyChannels(const Image& src, Image& dst, int offset)
{
    if (src.width() != dst.width() || src.height() != dst.height()
        || offset + src.channels() > dst.channels())
        throwInvalidArgument("copyChannels: shapes do not match");
    const int c = src.channels();
    parallelRows(src.height(), [&](int y0, int y1) {
        for (int y = y0; y < y1; ++y)
            for (int x = 0; x < src.width(); ++x)
                std::copy(src.at(x, y), src.at(x, y) + c, dst.at(x, y) + offset);
    });
}

} // namespace afn::nn
