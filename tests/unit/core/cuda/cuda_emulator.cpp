// SPDX-License-Identifier: Apache-2.0
// Host emulation of the CUDA afn kernels (see cuda_emulator.h). The loops here stand for the
// kernels' grids (temporal.cu, prepare.cu, conv.cu, filter_fuse.cu); the per-thread code is the
// kernels' own.
#include "cuda_emulator.h"

#include "base/exception.h"

#include <algorithm>
#include <cmath>

namespace afntest {

using namespace afn::cuda;

namespace {

float halfLo(std::uint32_t w)
{
    return halfToFloat(static_cast<std::uint16_t>(w & 0xffffu));
}
float halfHi(std::uint32_t w)
{
    return halfToFloat(static_cast<std::uint16_t>(w >> 16));
}

/// The quad butterflies of warp_ops.cuh: lane l adds lane l ^ 1, then lane l ^ 2.
void quadSum(float (&v)[32])
{
    float s1[32], s2[32];
    for (int l = 0; l < 32; ++l)
        s1[l] = v[l] + v[l ^ 1];
    for (int l = 0; l < 32; ++l)
        s2[l] = s1[l] + s1[l ^ 2];
    std::copy(s2, s2 + 32, v);
}
void quadMax(float (&v)[32])
{
    float s1[32], s2[32];
    for (int l = 0; l < 32; ++l)
        s1[l] = std::fmax(v[l], v[l ^ 1]);
    for (int l = 0; l < 32; ++l)
        s2[l] = std::fmax(s1[l], s1[l ^ 2]);
    std::copy(s2, s2 + 32, v);
}

/// Head logits of a tile for all lanes (filter_fuse.cu headLogits).
void headLogits(const ConvOperands& op, TileShape shape, int x0, int y0, HeadAccumulators (&h)[32])
{
    float c[kHeadTiles][32][4] = {};
    for (int kc = 0; kc < op.kChunks(); ++kc) {
        std::uint32_t a[32][4];
        for (int lane = 0; lane < 32; ++lane)
            loadConvA(op, shape, lane, x0, y0, 0, kc, a[lane]);
        for (int nt = 0; nt < kHeadTiles; ++nt) {
            std::uint32_t b[32][2];
            for (int lane = 0; lane < 32; ++lane)
                loadConvB(op, lane, 0, kc, nt, b[lane]);
            emulateMma(a, b, c[nt]);
        }
    }
    for (int lane = 0; lane < 32; ++lane) {
        for (int nt = 0; nt < kHeadTiles; ++nt)
            for (int i = 0; i < 4; ++i)
                h[lane].v[nt][i] = c[nt][lane][i];
        addHeadBias(h[lane], op.bias, lane);
    }
}

/// filter_fuse.cu softmaxFilter for all lanes.
template <typename Color>
void softmaxFilter(HeadAccumulators (&h)[32], int half, const Color& color, int (&x)[32],
    int (&y)[32], float (&rgb)[32][3])
{
    float m[32], s[32];
    for (int lane = 0; lane < 32; ++lane)
        m[lane] = lanePartialMax(h[lane], lane, half);
    quadMax(m);
    for (int lane = 0; lane < 32; ++lane)
        s[lane] = laneExpSum(h[lane], lane, half, m[lane]);
    quadSum(s);
    for (int lane = 0; lane < 32; ++lane)
        laneFilter(h[lane], lane, half, 1.0f / s[lane], color, x[lane], y[lane], rgb[lane]);
    for (int c = 0; c < 3; ++c) {
        float v[32];
        for (int lane = 0; lane < 32; ++lane)
            v[lane] = rgb[lane][c];
        quadSum(v);
        for (int lane = 0; lane < 32; ++lane)
            rgb[lane][c] = v[lane];
    }
}

} // namespace

void emulateMma(const std::uint32_t (&a)[32][4], const std::uint32_t (&b)[32][2], float (&c)[32][4])
{
    // PTX ISA, mma.m16n8k16 with .f16 A/B and .f32 C/D; groupID = lane >> 2,
    // threadID_in_group = lane % 4.
    float A[16][16], B[16][8];
    for (int lane = 0; lane < 32; ++lane) {
        const int gid = lane >> 2, tig = lane % 4;
        A[gid][tig * 2] = halfLo(a[lane][0]);
        A[gid][tig * 2 + 1] = halfHi(a[lane][0]);
        A[gid + 8][tig * 2] = halfLo(a[lane][1]);
        A[gid + 8][tig * 2 + 1] = halfHi(a[lane][1]);
        A[gid][tig * 2 + 8] = halfLo(a[lane][2]);
        A[gid][tig * 2 + 9] = halfHi(a[lane][2]);
        A[gid + 8][tig * 2 + 8] = halfLo(a[lane][3]);
        A[gid + 8][tig * 2 + 9] = halfHi(a[lane][3]);
        B[tig * 2][gid] = halfLo(b[lane][0]);
        B[tig * 2 + 1][gid] = halfHi(b[lane][0]);
        B[tig * 2 + 8][gid] = halfLo(b[lane][1]);
        B[tig * 2 + 9][gid] = halfHi(b[lane][1]);
    }
    for (int lane = 0; lane < 32; ++lane) {
        const int gid = lane >> 2, tig = lane % 4;
        for (int i = 0; i < 4; ++i) {
            const int row = i < 2 ? gid : gid + 8, col = tig * 2 + (i & 1);
            double sum = c[lane][i];
            for (int k = 0; k < 16; ++k)
                sum += static_cast<double>(A[row][k]) * B[k][col];
            c[lane][i] = static_cast<float>(sum);
        }
    }
}

void emulateTemporal(const TemporalBuffers& b, const FrameConstants& f, std::uint32_t* depthRange)
{
    for (int y = 0; y < b.height; ++y)
        for (int x = 0; x < b.width; ++x) {
            temporalPixel(b, f, x, y);
            if (b.depth) {
                const float z = b.depth[static_cast<std::size_t>(y) * b.width + x];
                if (isValidDepth(z)) {
                    depthRange[0] = std::min(depthRange[0], orderedKey(z));
                    depthRange[1] = std::max(depthRange[1], orderedKey(z));
                }
            }
        }
}

void emulatePrepare(const PrepareBuffers& b)
{
    const DepthScale ds = b.depth ? depthScale(b.depthRange[0], b.depthRange[1]) : DepthScale {};
    for (int yh = 0; yh < b.paddedHeight / 2; ++yh)
        for (int xh = 0; xh < b.paddedWidth / 2; ++xh)
            prepareBlock(b, ds, xh, yh);
}

void emulatePool(const std::uint16_t* in, int width, int height, int stride, std::uint16_t* out)
{
    const int wo = width / 2, ho = height / 2;
    auto at = [&](int x, int y, int c) {
        return halfToFloat(in[(static_cast<std::size_t>(y) * width + x) * stride + c]);
    };
    for (int y = 0; y < ho; ++y)
        for (int x = 0; x < wo; ++x)
            for (int c = 0; c < stride; ++c) {
                const float v = (at(2 * x, 2 * y, c) + at(2 * x + 1, 2 * y, c)
                                    + at(2 * x, 2 * y + 1, c) + at(2 * x + 1, 2 * y + 1, c))
                    / 4.0f;
                out[(static_cast<std::size_t>(y) * wo + x) * stride + c] = floatToHalf(v);
            }
}

namespace {

/// conv.cu's grid: every Row16 tile, all N tiles at once (the kernel's grouping over
/// gridDim.y does not change any value).
template <typename Store> void emulateConv(const ConvOperands& op, Store&& store)
{
    std::vector<float> acc(static_cast<std::size_t>(op.tiles) * 32 * 4);
    for (int y = 0; y < op.height; ++y)
        for (int x0 = 0; x0 < op.width; x0 += 16) {
            std::fill(acc.begin(), acc.end(), 0.0f);
            for (int tap = 0; tap < op.ksize * op.ksize; ++tap)
                for (int kc = 0; kc < op.kChunks(); ++kc) {
                    std::uint32_t a[32][4];
                    for (int lane = 0; lane < 32; ++lane)
                        loadConvA(op, TileShape::Row16, lane, x0, y, tap, kc, a[lane]);
                    for (int tile = 0; tile < op.tiles; ++tile) {
                        std::uint32_t b[32][2];
                        float c[32][4];
                        for (int lane = 0; lane < 32; ++lane) {
                            loadConvB(op, lane, tap, kc, tile, b[lane]);
                            for (int i = 0; i < 4; ++i)
                                c[lane][i] = acc[(tile * 32 + lane) * 4 + i];
                        }
                        emulateMma(a, b, c);
                        for (int lane = 0; lane < 32; ++lane)
                            for (int i = 0; i < 4; ++i)
                                acc[(tile * 32 + lane) * 4 + i] = c[lane][i];
                    }
                }
            for (int tile = 0; tile < op.tiles; ++tile)
                for (int lane = 0; lane < 32; ++lane) {
                    float c[4];
                    for (int i = 0; i < 4; ++i)
                        c[i] = acc[(tile * 32 + lane) * 4 + i];
                    store(lane, x0, y, tile, c);
                }
        }
}

} // namespace

void emulateConvRelu(const ConvOperands& op, const ReluOutput& out)
{
    emulateConv(op, [&](int lane, int x0, int y, int tile, const float(&c)[4]) {
        storeRelu(op, out, lane, x0, y, tile, c);
        if (tile == 0)
            storeZeroPadding(op, out, lane, x0, y);
    });
}

void emulateConvFinal(const ConvOperands& op, const FinalOutput& out)
{
    emulateConv(op, [&](int lane, int x0, int y, int tile, const float(&c)[4]) {
        if (tile == 0)
            storeFinal(op, out, lane, x0, y, c);
    });
}

void emulateFilterFuse(const FilterFuseArgs& a)
{
    const int halfWidth = a.head1.width, halfHeight = a.head1.height;
    const int paddedWidth = a.headTa.width;
    for (int yh = 0; yh < halfHeight; ++yh)
        for (int xh0 = 0; xh0 < halfWidth; xh0 += 16) {
            // 1. The 1-spp branch.
            float filtered1[16][3];
            {
                HeadAccumulators h[32];
                headLogits(a.head1, TileShape::Row16, xh0, yh, h);
                for (int half = 0; half < 2; ++half) {
                    int x[32], y[32];
                    float rgb[32][3];
                    for (int lane = 0; lane < 32; ++lane) {
                        x[lane] = xh0 + Fragment::group(lane) + 8 * half;
                        y[lane] = yh;
                    }
                    softmaxFilter(h, half, a.color1Half, x, y, rgb);
                    for (int lane = 0; lane < 32; lane += 4)
                        for (int c = 0; c < 3; ++c)
                            filtered1[Fragment::group(lane) + 8 * half][c] = rgb[lane][c];
                }
            }
            // 2. The TA branch.
            const int y0 = 2 * yh;
            for (int s = 0; s < 4; ++s) {
                const int x0 = 2 * xh0 + 8 * s;
                HeadAccumulators h[32];
                headLogits(a.headTa, TileShape::Block8x2, x0, y0, h);
                float alpha[32][2], dTa[2][32][3];
                for (int half = 0; half < 2; ++half) {
                    for (int lane = 0; lane < 32; ++lane)
                        alpha[lane][half] = sigmoid(h[lane & ~3].v[6][2 * half + 1]);
                    int x[32], y[32];
                    for (int lane = 0; lane < 32; ++lane) {
                        x[lane] = x0 + Fragment::group(lane);
                        y[lane] = y0 + half;
                    }
                    softmaxFilter(h, half, a.colorTa, x, y, dTa[half]);
                }
                for (int lane = 0; lane < 32; ++lane) {
                    const int g = Fragment::group(lane), t = Fragment::thread(lane);
                    const int x = x0 + g;
                    if (x >= paddedWidth)
                        continue;
                    const bool left = (g & 1) == 0;
                    const float* d1 = filtered1[4 * s + g / 2];
                    float fused[2][3];
                    for (int c = 0; c < 3; ++c) {
                        const float* own0 = dTa[0][lane];
                        const float* own1 = dTa[1][lane];
                        const float* oth0 = dTa[0][lane ^ 4];
                        const float* oth1 = dTa[1][lane ^ 4];
                        const float tl = left ? own0[c] : oth0[c], tr = left ? oth0[c] : own0[c];
                        const float bl = left ? own1[c] : oth1[c], br = left ? oth1[c] : own1[c];
                        for (int half = 0; half < 2; ++half)
                            fused[half][c] = fuse(
                                dTa[half][lane][c], alpha[lane][half], tl, tr, bl, br, d1[c]);
                    }
                    for (int half = 0; half < 2; ++half) {
                        const int y = y0 + half;
                        const std::size_t pixel = static_cast<std::size_t>(y) * paddedWidth + x;
                        if (a.fused) {
                            if (t < 3)
                                a.fused[3 * pixel + t] = component(fused[half], t);
                            const std::uint16_t* xPixel = a.x + pixel * kInputStride;
                            for (int k = 0; k < 4; ++k)
                                a.refineInput[pixel * kInputStride + 4 * t + k]
                                    = refineInputChannel(4 * t + k, fused[half], xPixel);
                        } else if (t < 3 && x < a.output.width && y < a.output.height) {
                            const std::size_t p = static_cast<std::size_t>(y) * a.output.width + x;
                            a.output.data[3 * p + t]
                                = remodulated(a.output, p, t, component(fused[half], t));
                        }
                    }
                }
            }
        }
}

// ---- The pipeline
// --------------------------------------------------------------------------------

void EmulatedAfnPipeline::Tensor::allocate(int w, int h, int channels)
{
    width = w;
    height = h;
    stride = channelStride(channels);
    // NaN halves: a value the kernels never wrote shows up in the results.
    data.assign(static_cast<std::size_t>(w) * h * stride, 0xffffu);
}

afn::Image EmulatedAfnPipeline::Tensor::toImage(int channels) const
{
    afn::Image img(width, height, channels);
    for (std::size_t p = 0; p < static_cast<std::size_t>(width) * height; ++p)
        for (int c = 0; c < channels; ++c)
            img.data()[p * channels + c] = halfToFloat(data[p * stride + c]);
    return img;
}

EmulatedAfnPipeline::EmulatedAfnPipeline(const afn::afnet::Network& net)
    : m_variant(net.variant())
    , m_refine(net.variant() == afn::afnet::Variant::Full)
{
    using L = afn::afnet::Network::Layer;
    for (int i = 0; i < 10; ++i) {
        const auto which = static_cast<L>(i);
        if (!m_refine && i >= static_cast<int>(L::Ref1))
            continue;
        int up = 0;
        if (which == L::Dec2)
            up = net.layer(L::Enc3).outChannels();
        else if (which == L::Dec1)
            up = net.layer(L::Dec2).outChannels();
        else if (which == L::HeadTa)
            up = net.layer(L::Dec1).outChannels();
        m_layers[i].packed = packConv(net.layer(which), up);
    }
}

ConvOperands EmulatedAfnPipeline::operands(
    const Layer& layer, const Tensor* up, const Tensor& same) const
{
    const PackedConv& pc = layer.packed;
    if ((up && (pc.upChunks() * kChunk != up->stride || 2 * up->width != same.width))
        || (!up && pc.upChunks() != 0) || pc.sameChunks() * kChunk != same.stride)
        afn::throwInvalidOperation("emulated CUDA afn: a layer does not match its inputs");
    ConvOperands op;
    op.up = up ? up->data.data() : nullptr;
    op.upStride = up ? up->stride : 0;
    op.upChunks = pc.upChunks();
    op.upWidth = up ? up->width : 0;
    op.same = same.data.data();
    op.sameStride = same.stride;
    op.sameChunks = pc.sameChunks();
    op.width = same.width;
    op.height = same.height;
    op.ksize = pc.ksize;
    op.weights = pc.weights.data();
    op.bias = pc.bias.data();
    op.tiles = pc.tiles();
    return op;
}

void EmulatedAfnPipeline::allocate(const afn::Frame& f)
{
    using L = afn::afnet::Network::Layer;
    if (f.width == m_width && f.height == m_height)
        return;
    m_width = f.width;
    m_height = f.height;
    m_paddedWidth = paddedSize(m_width);
    m_paddedHeight = paddedSize(m_height);
    const std::size_t n = static_cast<std::size_t>(m_width) * m_height;
    const float nan = std::nanf("");
    m_irradiance.assign(3 * n, nan);
    m_output.assign(3 * n, nan);
    for (int s = 0; s < 2; ++s) {
        m_accumulated[s].assign(3 * n, nan);
        m_history[s].assign(n, nan);
    }
    auto ch = [&](L l) { return m_layers[static_cast<int>(l)].packed.outChannels; };
    const int wp = m_paddedWidth, hp = m_paddedHeight;
    m_x.allocate(wp, hp, kInputChannels);
    m_xHalf.allocate(wp / 2, hp / 2, kInputChannels);
    m_e1.allocate(wp / 2, hp / 2, ch(L::Enc1));
    m_e1Pool.allocate(wp / 4, hp / 4, ch(L::Enc1));
    m_e2.allocate(wp / 4, hp / 4, ch(L::Enc2));
    m_e2Pool.allocate(wp / 8, hp / 8, ch(L::Enc2));
    m_e3.allocate(wp / 8, hp / 8, ch(L::Enc3));
    m_d2.allocate(wp / 4, hp / 4, ch(L::Dec2));
    m_d1.allocate(wp / 2, hp / 2, ch(L::Dec1));
    m_color1Half.assign(3 * static_cast<std::size_t>(wp / 2) * (hp / 2), nan);
    if (m_refine) {
        m_fused.assign(3 * static_cast<std::size_t>(wp) * hp, nan);
        m_refineInput.allocate(wp, hp, kRefineInputChannels);
        m_r1.allocate(wp, hp, ch(L::Ref1));
        m_r2.allocate(wp, hp, ch(L::Ref2));
    }
}

void EmulatedAfnPipeline::run(const afn::Frame& f, const FrameConstants& c, afn::Image& out)
{
    using L = afn::afnet::Network::Layer;
    allocate(f);
    const int s = m_slot, p = s ^ 1;
    // Upload.
    m_color.assign(f.color.data(), f.color.data() + f.color.size());
    m_albedo.assign(f.albedo.data(), f.albedo.data() + f.albedo.size());
    m_motion.assign(f.motion.data(), f.motion.data() + f.motion.size());
    m_position[s].assign(f.position.data(), f.position.data() + f.position.size());
    m_normal[s].assign(f.normal.data(), f.normal.data() + f.normal.size());
    m_depth[s].assign(f.depth.data(), f.depth.data() + f.depth.size());
    auto ptr = [](std::vector<float>& v) { return v.empty() ? nullptr : v.data(); };

    // TemporalFeatures.
    std::uint32_t range[2] = { kEmptyRangeMin, kEmptyRangeMax };
    TemporalBuffers b;
    b.width = m_width;
    b.height = m_height;
    b.color = m_color.data();
    b.albedo = ptr(m_albedo);
    b.motion = ptr(m_motion);
    b.position = ptr(m_position[s]);
    b.prevPosition = f.hasPosition() ? m_position[p].data() : nullptr;
    b.normal = ptr(m_normal[s]);
    b.prevNormal = f.hasNormal() ? m_normal[p].data() : nullptr;
    b.depth = ptr(m_depth[s]);
    b.prevDepth = f.hasDepth() ? m_depth[p].data() : nullptr;
    b.prevAccumulated = m_accumulated[p].data();
    b.prevHistoryLength = m_history[p].data();
    b.irradiance = m_irradiance.data();
    b.accumulated = m_accumulated[s].data();
    b.historyLength = m_history[s].data();
    emulateTemporal(b, c, range);
    const bool oneSpp = m_variant == afn::afnet::Variant::OneSpp;
    const bool ta = m_variant == afn::afnet::Variant::Ta;
    float* colorTa = oneSpp ? m_irradiance.data() : m_accumulated[s].data();
    PrepareBuffers pb;
    pb.width = m_width;
    pb.height = m_height;
    pb.paddedWidth = m_paddedWidth;
    pb.paddedHeight = m_paddedHeight;
    pb.color1 = ta ? m_accumulated[s].data() : m_irradiance.data();
    pb.colorTa = colorTa;
    pb.albedo = b.albedo;
    pb.normal = b.normal;
    pb.depth = b.depth;
    pb.depthRange = range;
    pb.x = m_x.data.data();
    pb.xHalf = m_xHalf.data.data();
    pb.color1Half = m_color1Half.data();
    emulatePrepare(pb);

    // KernelPrediction.
    auto layer = [&](L l) -> const Layer& { return m_layers[static_cast<int>(l)]; };
    auto conv = [&](L l, const Tensor* up, const Tensor& same, Tensor& o) {
        emulateConvRelu(operands(layer(l), up, same), ReluOutput { o.data.data(), o.stride });
    };
    auto pool = [&](const Tensor& in, Tensor& o) {
        emulatePool(in.data.data(), in.width, in.height, in.stride, o.data.data());
    };
    conv(L::Enc1, nullptr, m_xHalf, m_e1);
    pool(m_e1, m_e1Pool);
    conv(L::Enc2, nullptr, m_e1Pool, m_e2);
    pool(m_e2, m_e2Pool);
    conv(L::Enc3, nullptr, m_e2Pool, m_e3);
    conv(L::Dec2, &m_e3, m_e2, m_d2);
    conv(L::Dec1, &m_d2, m_e1, m_d1);

    // FilteringFusion.
    FinalOutput fo;
    fo.fused = m_refine ? m_fused.data() : nullptr;
    fo.albedo = b.albedo;
    fo.plainAlbedo = c.colorDemodulated;
    fo.data = m_output.data();
    fo.width = m_width;
    fo.height = m_height;
    FilterFuseArgs a;
    a.head1 = operands(layer(L::Head1), nullptr, m_d1);
    a.headTa = operands(layer(L::HeadTa), &m_d1, m_x);
    a.x = m_x.data.data();
    a.colorTa = PaddedColor { colorTa, m_width, m_height, m_paddedWidth, m_paddedHeight };
    a.color1Half = PlainColor { m_color1Half.data(), m_paddedWidth / 2, m_paddedHeight / 2 };
    if (m_refine) {
        a.fused = m_fused.data();
        a.refineInput = m_refineInput.data.data();
    } else {
        a.output = fo;
    }
    emulateFilterFuse(a);

    // Refinement.
    if (m_refine) {
        conv(L::Ref1, nullptr, m_refineInput, m_r1);
        conv(L::Ref2, nullptr, m_r1, m_r2);
        emulateConvFinal(operands(layer(L::Ref3), nullptr, m_r2), fo);
    }

    out = afn::Image(m_width, m_height, 3);
    std::copy(m_output.begin(), m_output.end(), out.data());
    m_irradianceImage = afn::Image(m_width, m_height, 3);
    std::copy(m_irradiance.begin(), m_irradiance.end(), m_irradianceImage.data());
    m_accumulatedImage = afn::Image(m_width, m_height, 3);
    std::copy(m_accumulated[s].begin(), m_accumulated[s].end(), m_accumulatedImage.data());
    m_slot ^= 1;
}

afn::Image EmulatedAfnPipeline::networkInput() const
{
    return m_x.toImage(kInputChannels);
}

afn::Image EmulatedAfnPipeline::decoderOutput() const
{
    return m_d1.toImage(
        m_layers[static_cast<int>(afn::afnet::Network::Layer::Dec1)].packed.outChannels);
}

} // namespace afntest
