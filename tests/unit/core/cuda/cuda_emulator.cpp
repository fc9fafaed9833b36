// SPDX-License-Identifier: Apache-2.0
// Host emulation of the CUDA afn kernels (see cuda_emulator.h). The loops here stand for the
// kernels' grids (temporal.cu, prepare.cu, conv.cu, filter_fuse.cu); the per-thread code is the
// kernels' own.
#include "cuda_emulator.h"

#include <algorithm>
#include <cmath>
#include <vector>

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

void emulateAuxPrefilter(const AuxBuffers& b, const TemporalBuffers& t, const FrameConstants& f)
{
    AuxState& s = *b.state;
    for (unsigned& c : s.counts)
        c = 0u;
    if (!f.hasHistory) {
        s.decided = 0;
        s.hasHistory = 0;
    }
    for (int y = 0; y < b.height; ++y)
        for (int x = 0; x < b.width; ++x) {
            const unsigned speckled = auxFlagsPixel(b, x, y);
            for (int kind = 0; kind < 3; ++kind)
                s.counts[kind] += (speckled >> kind) & 1u;
        }
    auxDecide(b, f);
    if (b.normal || b.depth)
        for (int y = 0; y < b.height; ++y)
            for (int x = 0; x < b.width; ++x)
                auxGeometryPixel(b, x, y);
    if (b.albedo)
        for (int y = 0; y < b.height; ++y)
            for (int x = 0; x < b.width; ++x)
                auxAlbedoPixel(b, t, f, x, y);
}

void emulateTemporal(const TemporalBuffers& b, const TrustBuffers& t, const FrameConstants& f,
    std::uint32_t* depthRange)
{
    for (int y = 0; y < b.height; ++y)
        for (int x = 0; x < b.width; ++x) {
            temporalGather(b, f, x, y);
            if (b.depth) {
                const float z = b.depth[static_cast<std::size_t>(y) * b.width + x];
                if (isValidDepth(z)) {
                    depthRange[0] = std::min(depthRange[0], orderedKey(z));
                    depthRange[1] = std::max(depthRange[1], orderedKey(z));
                }
            }
        }
    const bool measured = trustMeasured(f.hasHistory, f.antilag);
    if (measured) {
        for (int y = 0; y < t.height; ++y)
            for (int bx = 0; bx < t.blocksX; ++bx)
                trustRowSums(t, b.irradiance, b.accumulated, b.historyLength, y, bx);
        for (int gy = 0; gy * kTrustCoarse < t.blocksY; ++gy)
            for (int gx = 0; gx * kTrustCoarse < t.blocksX; ++gx)
                trustGroup(t, f.antilag, gx, gy);
        for (int by = 0; by < t.blocksY; ++by)
            for (int bx = 0; bx < t.blocksX; ++bx)
                *t.cutPixels += trustSoftMin(t, bx, by);
    }
    for (int y = 0; y < b.height; ++y)
        for (int x = 0; x < b.width; ++x)
            temporalBlend(b, f, measured ? pixelTrust(t, x, y) : 1.0f, x, y);
}

void emulateUndemodulate(
    const float* irradiance, const float* albedo, bool plain, float* out, int w, int h)
{
    for (std::size_t i = 0; i < 3 * static_cast<std::size_t>(w) * h; ++i)
        out[i] = undemodulateValue(irradiance[i], albedo[i], plain);
}

float emulateHighlightLimit(const float* ta, int w, int h, float factor)
{
    unsigned counts[kHighlightBins] = {};
    long long n = 0;
    for (int y = 0; y < h; y += kHighlightStride)
        for (int x = 0; x < w; x += kHighlightStride, ++n)
            ++counts[highlightBin(
                highlightLargest(ta + 3 * (static_cast<std::size_t>(y) * w + x)))];
    return highlightLimitFromCounts(counts, n, factor);
}

void emulateHighlightClamp(const float* in, float limit, float* out, int w, int h)
{
    for (std::size_t i = 0; i < 3 * static_cast<std::size_t>(w) * h; ++i)
        out[i] = clampHighlight(in[i], limit);
}

void emulateHighlightExcess(
    const float* ta, const float* albedo, bool plain, float limit, float* out, int w, int h)
{
    for (std::size_t i = 0; i < static_cast<std::size_t>(w) * h; ++i)
        addHighlightExcess(
            ta + 3 * i, albedo ? albedo + 3 * i : nullptr, plain, limit, out + 3 * i);
}

void emulatePrepare(const PrepareBuffers& b)
{
    const DepthScale ds = b.depth ? depthScale(b.depthRange[0], b.depthRange[1]) : DepthScale {};
    for (int yh = 0; yh < b.paddedHeight / 2; ++yh)
        for (int xh = 0; xh < b.paddedWidth / 2; ++xh)
            prepareBlock(b, ds, xh, yh);
}

void emulateAlbedoTrust(const AlbedoTrustBuffers& b)
{
    for (int yh = 0; yh < b.halfHeight; ++yh)
        for (int xh = 0; xh < b.halfWidth; ++xh)
            albedoTrustBlock(b, xh, yh);
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

void emulateConvLinear(const ConvOperands& op, const LinearOutput& out)
{
    emulateConv(op, [&](int lane, int x0, int y, int tile, const float(&c)[4]) {
        storeLinear(op, out, lane, x0, y, tile, c);
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
                                = outputValue(a.output, x, y, t, component(fused[half], t));
                        }
                    }
                }
            }
        }
}

void emulateFlip(const float* src, float* dst, int channels, int w, int h, bool fx, bool fy)
{
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            flipPixel(src, dst, channels, w, h, x, y, fx, fy);
}

void emulateAddPass(const float* pass, float* sum, int w, int h, bool fx, bool fy, bool first)
{
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            addPassPixel(pass, sum, w, h, x, y, fx, fy, first);
}

void emulateAveragePasses(const float* sum, const FinalOutput& out)
{
    for (int y = 0; y < out.height; ++y)
        for (int x = 0; x < out.width; ++x)
            averagePassesPixel(sum, out, x, y);
}

void emulateTaa(const TaaBuffers& a, const TemporalBuffers& t, const TrustBuffers* trust,
    const FrameConstants& f)
{
    for (int y = 0; y < a.height; ++y)
        for (int x = 0; x < a.width; ++x)
            taaPixel(a, t, f, trust, x, y);
}

void emulatePostFilter(const PostFilterSources& s, const PostFilterPlanes& g, const float* input,
    float* output, float* scratch0, float* scratch1)
{
    for (int y = 0; y < s.height; ++y)
        for (int x = 0; x < s.width; ++x)
            postFilterGuidePixel(s, g, x, y);
    const float* in = input;
    for (int pass = 0; pass < kPostFilterIterationsDevice; ++pass)
        for (int half = 0; half < 2; ++half) {
            const bool last = pass == kPostFilterIterationsDevice - 1 && half == 1;
            float* out = last ? output : (half == 0 ? scratch0 : scratch1);
            for (int y = 0; y < s.height; ++y)
                for (int x = 0; x < s.width; ++x)
                    postFilterHalfPixel(g, in, out, s.width, s.height, x, y, half == 0, 1 << pass);
            in = out;
        }
}

} // namespace afntest
