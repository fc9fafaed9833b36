// SPDX-License-Identifier: Apache-2.0
// Transposed 2x2 stride-2 convolution (see nn/conv_transpose.h).
#include "nn/conv_transpose.h"

#include "base/exception.h"
#include "base/parallel.h"

#include <algorithm>

namespace afn::nn {

void ConvTranspose2x2::load(const WeightsArchive& a, const std::string& name, int expectedIn)
{
    const WeightTensor& w = a.tensor(name + ".weight");
    const WeightTensor& b = a.tensor(name + ".bias");
    auto bad = [&](const std::string& why) {
        throwInvalidArgument(
            "invalid or corrupted weights (" + a.source() + "): '" + name + ".weight': " + why);
    };
    if (w.dims.size() != 4 || w.dims[2] != 2 || w.dims[3] != 2)
        bad("expected (in, out, 2, 2)");
    const int in = static_cast<int>(w.dims[0]), out = static_cast<int>(w.dims[1]);
    if (in != expectedIn)
        bad("expected " + std::to_string(expectedIn) + " input channels");
    if (out < 1 || out > 1024 || b.dims.size() != 1 || b.dims[0] != out)
        bad("output channels or bias shape do not match");
    m_in = in;
    m_out = out;
    m_b = b.data;
    m_w.assign(static_cast<std::size_t>(4) * in * out, 0.0f);
    for (int i = 0; i < in; ++i)
        for (int o = 0; o < out; ++o)
            for (int t = 0; t < 4; ++t)
                m_w[(static_cast<std::size_t>(t) * in + i) * out + o]
                    = w.data[(static_cast<std::size_t>(i) * out + o) * 4 + t];
}

void ConvTranspose2x2::run(const Image& in, Image& out, int offset, bool relu) const
{
    if (out.width() != 2 * in.width() || out.height() != 2 * in.height() || in.channels() != m_in
        || offset + m_out > out.channels())
        throwInvalidArgument("ConvTranspose2x2: image shapes do not match the layer");
    const int cin = m_in, cout = m_out;
    parallelRows(in.height(), [&](int y0, int y1) {
        std::vector<float> acc(cout);
        for (int y = y0; y < y1; ++y)
            for (int x = 0; x < in.width(); ++x) {
                const float* src = in.at(x, y);
                for (int t = 0; t < 4; ++t) {
                    std::copy(m_b.begin(), m_b.end(), acc.begin());
                    const float* w = m_w.data() + static_cast<std::size_t>(t) * cin * cout;
                    for (int i = 0; i < cin; ++i) {
                        const float v = src[i];
                        const float* wi = w + static_cast<std::size_t>(i) * cout;
                        for (int o = 0; o < cout; ++o)
                            acc[o] += v * wi[o];
                    }
                    float* dst = out.at(2 * x + (t & 1), 2 * y + (t >> 1)) + offset;
                    for (int o = 0; o < cout; ++o)
                        dst[o] = relu ? std::max(acc[o], 0.0f) : acc[o];
                }
            }
    });
}

} // namespace afn::nn
