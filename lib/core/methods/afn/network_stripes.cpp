// SPDX-License-Identifier: Apache-2.0
// The AFN forward pass in horizontal stripes (Network::run, see methods/afn/network.h).
//
// Memory: the whole-frame path stores ~50 floats per padded pixel (x 13, d1 6 at half
// res, e1 4, fused/d_TA/out 3 each, ...): 190 MiB per megapixel, 6 GiB at 8K. Here the padded
// frame is cut into near-equal stripes of at most kStripeRows output rows (multiples of 8, so
// that every level of the U-Net has whole rows), as many as a multiple of the thread count, so
// that the threads end together (run()). A stripe [Y0, Y1) works in a window of padded rows
// [Y0 - kHalo, Y1 + kHalo) clipped to the frame, and at level l (1/2^l resolution) in the window
// rows scaled by 2^-l; every buffer is window-sized and comes from a pool of workspaces (one per
// concurrently running stripe, reused across frames): memory is O(threads x width x
// (kStripeRows + 2 kHalo)), whatever the frame height.
//
// Rows computed per layer for output rows [Y0, Y1) (global row numbers of the layer's level, each
// clipped to the window; a 3x3 conv needs its input one row further, D two input rows per row,
// U row r reads r / 2). Derived backwards from the output:
//   refine    [Y0, Y1)        reads fused [Y0-3, Y1+3)
//   fusion    half [Y0/2-2, Y1/2+2) = full [Y0-4, Y1+4); reads d1 there, x there, colorTa
//             [Y0-7, Y1+7), D(color1) half [Y0/2-5, Y1/2+5)
//   d1 (1/2)  [Y0/2-2, Y1/2+2)  reads e1 [Y0/2-3, Y1/2+3), d2 [Y0/4-2, Y1/4+2)
//   d2 (1/4)  [Y0/4-2, Y1/4+2)  reads e2 [Y0/4-3, Y1/4+3), e3 [Y0/8-2, Y1/8+2)
//   e3 (1/8)  [Y0/8-2, Y1/8+2)  reads D(e2) [Y0/8-3, Y1/8+3) = e2 [Y0/4-6, Y1/4+6)
//   e2 (1/4)  [Y0/4-6, Y1/4+6)  reads D(e1) [Y0/4-7, Y1/4+7) = e1 [Y0/2-14, Y1/2+14)
//   e1 (1/2)  [Y0/2-14, Y1/2+14) reads D(x) [Y0/2-15, Y1/2+15) = x [Y0-30, Y1+30)
//   albedo trust (albedo_trust.h) t half [Y0/2-5, Y1/2+5) reads e1 [Y0/2-6, Y1/2+6); the colours
//             are rescaled over [Y0-10, Y1+10) (what the pooling and the filtering read)
// so kHalo = 32 (30 rounded up to 8, keeping the window on the 1/8 grid: U's row r / 2 and D's
// rows 2r, 2r+1 then map window-local rows to window-local rows). The pointwise buffers (x, D(x),
// colours, the pools) are filled over the whole window; the convolutions run on their rows only.
//
// Exactness: every value is computed by the same kernel, with the same operations in the same
// order, as in the whole-frame path (the conv kernels' summation order does not depend on how
// rows are split, nn/conv.h). A window's buffers read zero outside the window, which is the
// frame's zero padding where the window reaches the frame border, and is never read elsewhere
// (the rows above need at most kHalo - 2 rows of margin). So run() equals runWholeFrame() bit for
// bit (tests/unit/core/methods/afn/test_afn_stripes.cpp), for every thread count.
//
// Cost: the halos are computed by both neighbouring stripes: at kStripeRows = 64 about 15 % more
// multiply-adds than the frame needs (mostly the cheap encoder levels), not counted in the stage
// GFLOP. A stripe's working set (a few MB per layer at 4K) replaces frame-sized streams. The
// input rows (tone map, x, the colours) two consecutive windows share are not filled twice where
// one workspace runs both stripes: the pool hands a stripe the workspace that holds the previous
// window of the same run, and runStripe moves the shared rows up (the same values; at 720p the
// input preparation fell from about 23.5 to 18.5 ms of wall time per frame, 2 threads).
//
// Work skipping: with a work mask, only the 8-row blocks (the 1/8 grid a stripe must
// start on) that hold a non-zero pixel of it are computed: each run of such blocks is cut into
// stripes of at most kStripeRows from its first row. The other rows are the temporal accumulation
// in.colorTa (the cheap path; afn_method.cpp remodulates it as the network output). The argument
// above holds for any stripe bounds on the 1/8 grid, so computed rows are bit-identical with or
// without the mask. Each run pays its own halos: a sky above the subject costs one halo, not a
// stripe's worth of rows.
#include "methods/afn/network.h"
#include "methods/afn/work_rows.h"

#include "base/exception.h"
#include "base/parallel.h"
#include "methods/afn/fusion.h"

#include <tbb/task_arena.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <cstring>
#include <mutex>
#include <vector>

namespace afn::afnet {

namespace {

constexpr int kStripeRows = 64; // output rows per stripe (multiple of 8)
constexpr int kHalo = 32; // window rows above and below a stripe (multiple of 8, >= 30)
constexpr int kRefineRows = 32; // refinement sub-strips within a stripe (bounds its buffers)
static_assert(kStripeRows % 8 == 0 && kHalo % 8 == 0 && kHalo >= 30);

/// Window-local rows [y0, y1) of level `level` for the global rows [lo, hi) of that level.
struct Rows {
    int y0, y1;
};

} // namespace

struct Network::StripeWorkspace {
    Image x, color1, colorTa, color1Half, xHalf, e1, e1Pool, e2, e2Pool, e3, d2, d1, fused;
    Image trust; ///< the albedo trust's t (half res; weights with albedoTrust=1)
    std::vector<float> out; ///< the stripe's refined rows, padded width
    /// The run and the padded rows [filledW0, filledW1) that x, color1 and colorTa hold.
    std::uint64_t filledRun = 0;
    int filledW0 = 0, filledW1 = 0;
};

namespace {

/// Move rows [from, from + count) of `img` to rows [0, count) (the window moved down).
void shiftRowsUp(Image& img, int from, int count)
{
    const std::size_t row = static_cast<std::size_t>(img.width()) * img.channels();
    std::memmove(img.at(0, 0), img.at(0, from), sizeof(float) * row * count);
}

/// Unique per Network::run() across every network (their workspaces may be shared).
std::atomic<std::uint64_t> g_runs { 0 };

} // namespace

struct Network::WorkspacePool {
    std::mutex mutex;
    std::vector<std::unique_ptr<StripeWorkspace>> free;
    double ms[kStages] = {}; ///< thread milliseconds per stage of the current run
    double inputMs = 0.0; ///< of ms[prediction], the input preparation's
    int rowsReused = 0; ///< Network::inputRowsReused of the current run

    /// A free workspace, preferably one whose input rows the window starting at padded row `w0`
    /// of run `runId` can take over (runStripe), else the last one given back.
    std::unique_ptr<StripeWorkspace> take(std::uint64_t runId, int w0)
    {
        std::lock_guard<std::mutex> lock(mutex);
        if (free.empty())
            return std::make_unique<StripeWorkspace>();
        auto it = std::find_if(free.begin(), free.end(), [&](const auto& ws) {
            return ws->filledRun == runId && w0 > ws->filledW0 && w0 < ws->filledW1;
        });
        if (it == free.end())
            it = std::prev(free.end());
        std::unique_ptr<StripeWorkspace> ws = std::move(*it);
        free.erase(it);
        return ws;
    }
    void give(std::unique_ptr<StripeWorkspace> ws, const double* stageMs, double stripeInputMs,
        int stripeRowsReused)
    {
        std::lock_guard<std::mutex> lock(mutex);
        inputMs += stripeInputMs;
        rowsReused += stripeRowsReused;
        free.push_back(std::move(ws));
        for (int k = 0; k < kStages; ++k)
            ms[k] += stageMs[k];
    }
};

void Network::runStripe(const Inputs& in, int y0, int y1, StripeWorkspace& ws, Image& out,
    double* ms, double* inputMs, std::uint64_t runId, int* rowsReused) const
{
    using Clock = std::chrono::steady_clock;
    const Clock::time_point t0 = Clock::now();
    const int wp = paddedSize(m_width), hp = paddedSize(m_height);
    const int w0 = std::max(0, y0 - kHalo), w1 = std::min(hp, y1 + kHalo), n = w1 - w0;
    auto rows = [&](int level, int lo, int hi) {
        const int a = w0 >> level, b = w1 >> level;
        return Rows { std::clamp(lo, a, b) - a, std::clamp(hi, a, b) - a };
    };
    auto conv = [](const nn::Conv& c, const Image* up, const Image& same, Image& dst, Rows r) {
        dst.reshape(same.width(), same.height(), c.outChannels());
        c.runRows(up, same, r.y0, r.y1, dst.at(0, r.y0),
            static_cast<long>(dst.width()) * dst.channels(), dst.channels(), true);
    };
    auto pool = [](const Image& src, Image& dst, Rows r) {
        dst.reshape(src.width() / 2, src.height() / 2, src.channels());
        nn::down2Rows(src, dst, r.y0, r.y1);
    };
    // The workspace's images change shape between the first, the inner and the last stripes of a
    // frame: reshape (no zeroing pass). Every row a step reads is written by an earlier step of
    // this stripe (each layer's rows are the next one's plus its halo; rows past the window are
    // the kernels' zero padding, not stored rows), so no value of an earlier stripe is read
    // (test_afn_stripes.cpp: stripes against the whole-frame path, bit for bit).
    // Kernel prediction. The input rows this workspace filled for the previous stripe of the same
    // run (the window moved down, same height) are moved, not computed again: the tone map and
    // the input over the halo rows the two windows share (the same values: fillInput is per row).
    // The windows of a run's stripes may differ in height (run(): near-equal stripes); rows keep
    // their layout (padded width x channels) whatever the height, so the shared rows are moved
    // while the images still hold the previous window, then the images take this one's height.
    const int filled = ws.filledW1 - ws.filledW0;
    const bool sameRows = ws.x.width() == wp && ws.x.height() == filled
        && ws.x.channels() == inputChannels() && ws.color1.sameShape(ws.colorTa)
        && ws.color1.width() == wp && ws.color1.height() == filled && ws.color1.channels() == 3;
    // With the albedo trust the colours are rescaled in place below: nothing is taken over.
    const bool reuse = !m_albedoTrust && sameRows && ws.filledRun == runId && w0 > ws.filledW0
        && w0 < ws.filledW1 && w1 >= ws.filledW1;
    int fillFrom = w0;
    if (reuse) {
        for (Image* img : { &ws.x, &ws.color1, &ws.colorTa })
            shiftRowsUp(*img, w0 - ws.filledW0, ws.filledW1 - w0);
        fillFrom = ws.filledW1;
        *rowsReused += ws.filledW1 - w0;
    }
    ws.x.reshape(wp, n, inputChannels());
    ws.color1.reshape(wp, n, 3);
    ws.colorTa.reshape(wp, n, 3);
    fillInput(in, fillFrom, w1, w0, ws.x, ws.color1, ws.colorTa);
    ws.filledRun = runId, ws.filledW0 = w0, ws.filledW1 = w1;
    if (!m_albedoTrust) // else once the colours are rescaled, below
        pool(ws.color1, ws.color1Half, rows(1, y0 / 2 - 5, y1 / 2 + 5));
    const Clock::time_point tInput = Clock::now(); // the input is ready (predictionInputMs)
    pool(ws.x, ws.xHalf, rows(1, y0 / 2 - 15, y1 / 2 + 15));
    conv(m_enc1, nullptr, ws.xHalf, ws.e1, rows(1, y0 / 2 - 14, y1 / 2 + 14));
    if (m_albedoTrust) { // albedo_trust.h: t where the filtering reads the colours, then D(r_1spp)
        const Rows t = rows(1, y0 / 2 - 5, y1 / 2 + 5), c = rows(0, y0 - 10, y1 + 10);
        ws.trust.reshape(ws.e1.width(), ws.e1.height(), 1);
        albedoTrustRows(m_headG, ws.e1, t.y0, t.y1, ws.trust);
        applyAlbedoTrustRows(ws.x, ws.trust, c.y0, c.y1, ws.color1);
        applyAlbedoTrustRows(ws.x, ws.trust, c.y0, c.y1, ws.colorTa);
        pool(ws.color1, ws.color1Half, t);
    }
    pool(ws.e1, ws.e1Pool, rows(2, y0 / 4 - 7, y1 / 4 + 7));
    conv(m_enc2, nullptr, ws.e1Pool, ws.e2, rows(2, y0 / 4 - 6, y1 / 4 + 6));
    pool(ws.e2, ws.e2Pool, rows(3, y0 / 8 - 3, y1 / 8 + 3));
    conv(m_enc3, nullptr, ws.e2Pool, ws.e3, rows(3, y0 / 8 - 2, y1 / 8 + 2));
    conv(m_dec2, &ws.e3, ws.e2, ws.d2, rows(2, y0 / 4 - 2, y1 / 4 + 2));
    conv(m_dec1, &ws.d2, ws.e1, ws.d1, rows(1, y0 / 2 - 2, y1 / 2 + 2));
    const Clock::time_point t1 = Clock::now();
    // Filtering and fusion.
    ws.fused.reshape(wp, n, 3);
    FusionInputs fin;
    fin.d1 = &ws.d1;
    fin.x = &ws.x;
    fin.colorTa = &ws.colorTa;
    fin.color1Half = &ws.color1Half;
    fin.head1 = &m_head1;
    fin.headTa = &m_headTa;
    FusionOutputs fout;
    fout.fused = &ws.fused;
    const Rows f = rows(1, y0 / 2 - 2, y1 / 2 + 2);
    filterAndFuseRows(fin, fout, f.y0, f.y1);
    const Clock::time_point t2 = Clock::now();
    // Refinement into ws.out, then the crop into `out`.
    const long row = static_cast<long>(wp) * 3;
    ws.out.resize(static_cast<std::size_t>(y1 - y0) * row);
    for (int y = y0; y < y1; y += kRefineRows) {
        const int e = std::min(y1, y + kRefineRows);
        float* dst = ws.out.data() + (y - y0) * row;
        if (m_variant == Variant::Full)
            refineRows(ws.fused, ws.x, y - w0, e - w0, dst, row);
        else
            std::copy(ws.fused.at(0, y - w0), ws.fused.at(0, e - w0), dst);
        if (m_albedoTrust) // back to the albedo-demodulated space (albedo_trust.h)
            undoAlbedoTrustRows(ws.x, ws.trust, y - w0, e - w0, wp, dst, row);
    }
    for (int y = y0; y < std::min(y1, m_height); ++y) {
        const float* src = ws.out.data() + (y - y0) * row;
        std::copy(src, src + 3 * m_width, out.at(0, y));
    }
    const Clock::time_point t3 = Clock::now();
    auto msOf = [](Clock::time_point a, Clock::time_point b) {
        return std::chrono::duration<double, std::milli>(b - a).count();
    };
    *inputMs += msOf(t0, tInput);
    ms[0] += msOf(t0, t1);
    ms[1] += msOf(t1, t2);
    ms[2] += msOf(t2, t3);
}

void Network::run(const Inputs& given, Image& out, const Image* work)
{
    using Clock = std::chrono::steady_clock;
    const Clock::time_point start = Clock::now();
    const Inputs in = checkInputs(given);
    if (m_variant == Variant::Large) { // whole frame, every row (network_large.h)
        m_large.run(in, out, m_stageMs);
        m_inputMs = 0.0;
        m_skippedRows = 0;
        m_stripes = 1;
        return;
    }
    if (m_quarter) { // whole frame, every row (quarter_scale.h)
        runWholeFrame(given, out);
        m_skippedRows = 0;
        m_stripes = 1;
        return;
    }
    const int w = m_width, h = m_height, hp = paddedSize(h);
    const bool masked = work && !work->empty();
    if (masked && (work->width() != w || work->height() != h || work->channels() != 1))
        throwInvalidArgument("AFN: the work mask must be 1 channel of the frame's size");
    out.resize(w, h, 3);
    if (!m_pool)
        m_pool = std::make_shared<WorkspacePool>();
    WorkspacePool& pool = *m_pool;
    std::fill(pool.ms, pool.ms + kStages, 0.0);
    pool.inputMs = 0.0;
    pool.rowsReused = 0;
    const std::uint64_t runId = ++g_runs;
    const Image& cheap = given.colorTa ? *given.colorTa : *in.colorTa;
    // Stripes [y0, y1) of padded rows; rows of the frame in none take the cheap path. A run of
    // rows is cut into near-equal stripes on the 8-row grid, at most kStripeRows each, their
    // count a multiple of the thread count where the run has the blocks for it: with 64-row
    // stripes a 720-row frame made 11 whole stripes and one of 16 rows, and on 2 threads one
    // thread computed 48 rows more than the other while that one waited (about 6 ms a frame).
    const int threads = std::max(1, tbb::this_task_arena::max_concurrency());
    std::vector<std::pair<int, int>> stripes;
    auto addRun = [&](int y0, int y1) {
        const int blocks = (y1 - y0 + 7) / 8, most = kStripeRows / 8;
        const int count
            = std::min(blocks, ((blocks + most - 1) / most + threads - 1) / threads * threads);
        for (int k = 0; k < count; ++k) {
            const int b0 = static_cast<int>(static_cast<long>(k) * blocks / count);
            const int b1 = static_cast<int>(static_cast<long>(k + 1) * blocks / count);
            stripes.emplace_back(y0 + 8 * b0, std::min(y1, y0 + 8 * b1));
        }
    };
    // The rows of the 8-row blocks with work (work_rows.h; a block starts below h: hp - h < 8).
    const std::vector<char> computed = computedRows(masked ? work : nullptr, h);
    if (!masked) {
        addRun(0, hp);
    } else {
        int runStart = -1; // first row of the current run of blocks with work
        for (int y = 0; y <= hp; y += 8) {
            const bool needed = y < hp && computed[static_cast<std::size_t>(y)];
            if (needed && runStart < 0)
                runStart = y;
            if (!needed && runStart >= 0) {
                addRun(runStart, y);
                runStart = -1;
            }
        }
    }
    m_skippedRows = static_cast<int>(std::count(computed.begin(), computed.end(), 0));
    if (m_skippedRows > 0)
        parallelRows(h, [&](int y0, int y1) {
            for (int y = y0; y < y1; ++y)
                if (!computed[y])
                    std::copy(cheap.at(0, y), cheap.at(0, y) + 3 * w, out.at(0, y));
        });
    parallelFor(static_cast<int>(stripes.size()), [&](int s) {
        std::unique_ptr<StripeWorkspace> ws
            = pool.take(runId, std::max(0, stripes[s].first - kHalo));
        double ms[kStages] = {}, inputMs = 0.0;
        int rowsReused = 0;
        runStripe(
            in, stripes[s].first, stripes[s].second, *ws, out, ms, &inputMs, runId, &rowsReused);
        pool.give(std::move(ws), ms, inputMs, rowsReused);
    });
    m_stripes = static_cast<int>(stripes.size());
    m_inputRowsReused = pool.rowsReused;
    // The stages interleave across threads: split the wall time by their thread time.
    const double wall = std::chrono::duration<double, std::milli>(Clock::now() - start).count();
    double total = 0.0;
    for (double v : pool.ms)
        total += v;
    for (int k = 0; k < kStages; ++k)
        m_stageMs[k] = total > 0.0 ? wall * pool.ms[k] / total : 0.0;
    m_inputMs = total > 0.0 ? wall * pool.inputMs / total : 0.0;
}

} // namespace afn::afnet
