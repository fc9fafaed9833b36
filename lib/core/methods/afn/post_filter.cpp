// SPDX-License-Identifier: Apache-2.0
// afn's edge-aware post-filter (post_filter.h): the guide planes and noise scale once per frame,
// then the six half-passes row by row through small rings of rows (BandPasses), one band of the
// frame per task, each row filtered by the row kernel (post_filter_row.h). So the colour between
// half-passes stays in the processor's cache: a frame's colour planes do not fit there, and
// half-passes that each cross the whole frame are bound by memory traffic (docs/performance.md).
// The last half-pass writes the output interleaved.
#include "methods/afn/post_filter.h"

#include "base/parallel.h"
#include "cpu/rgb_rows.h"
#include "methods/afn/post_filter_row.h"

#include <tbb/task_arena.h>

#include <algorithm>
#include <cstddef>

namespace afn::afnet {

namespace {

/// Rows of the horizontal half of iteration `it` that a band's first output row needs before
/// it: the reach of the vertical halves from `it` on, 2 (1 << it) + ... + 2 (1 << last).
constexpr int bandHalo(int it)
{
    return it == kPostFilterIterations ? 0 : 2 * (1 << it) + bandHalo(it + 1);
}

/// Rows of a band's storage: a ring per iteration for its horizontal half's output, holding the
/// 4 step + 1 rows its vertical half reads, and one row for a vertical half's output (or the
/// radiance's row), read at once by the next horizontal half.
constexpr int bandRingRows(int it)
{
    return 4 * (1 << it) + 1;
}
constexpr int bandRows()
{
    int rows = 1;
    for (int it = 0; it < kPostFilterIterations; ++it)
        rows += bandRingRows(it);
    return rows;
}

/// Floats of a band's row of one plane: the width and a cache line, so that the rows' planes
/// start at different offsets within a page.
std::size_t bandPitch(int w)
{
    return static_cast<std::size_t>(w) + kPostFilterPlaneStagger;
}

/// The passes of the rows of one band of the frame, row by row: every half-pass row is computed
/// when the next half-pass first reads it, into a small ring of rows, so the colour stays in the
/// processor's cache between the six half-passes instead of crossing memory six times. A band
/// computes the rows of the earlier half-passes its first rows read before them (bandHalo), as
/// the band above computes them too: the same values, as each row is the same computation.
class BandPasses {
public:
    BandPasses(const Image& radiance, const PostFilterGuidePlanes& g, float* storage, Image& out)
        : m_radiance(radiance)
        , m_g(g)
        , m_w(radiance.width())
        , m_h(radiance.height())
        , m_out(out)
    {
        const std::size_t pitch = bandPitch(m_w);
        float* next = storage;
        for (int c = 0; c < 3; ++c, next += pitch)
            m_row[c] = next;
        for (int it = 0; it < kPostFilterIterations; ++it) {
            m_ringBase[it] = next;
            next += 3 * static_cast<std::size_t>(bandRingRows(it)) * pitch;
            postFilterTaps(true, 1 << it, m_horizontal[it]);
            postFilterTaps(false, 1 << it, m_vertical[it]);
        }
    }

    /// Output rows [y0, y1).
    void run(int y0, int y1)
    {
        for (int it = 0; it < kPostFilterIterations; ++it)
            m_next[it] = std::max(0, y0 - bandHalo(it));
        for (int y = y0; y < y1; ++y)
            verticalRow(kPostFilterIterations - 1, y);
    }

private:
    /// Plane c of row y of iteration it's ring.
    float* ringRow(int it, int y, int c) const
    {
        const std::size_t pitch = bandPitch(m_w);
        const std::size_t slot = static_cast<std::size_t>(y % bandRingRows(it));
        return m_ringBase[it] + (3 * slot + static_cast<std::size_t>(c)) * pitch;
    }

    /// Computes iteration it's horizontal-half rows up to `last`.
    void needHorizontal(int it, int last)
    {
        for (; m_next[it] <= last; ++m_next[it])
            horizontalRow(it, m_next[it]);
    }

    /// Row y of iteration it's horizontal half, from the previous iteration's vertical half (or
    /// the radiance) written into the band's row first.
    void horizontalRow(int it, int y)
    {
        if (it == 0)
            cpu::deinterleaveRgbRow(m_radiance.at(0, y), m_row[0], m_row[1], m_row[2], m_w);
        else
            verticalRow(it - 1, y);
        PostFilterRow row {};
        const std::size_t guides = static_cast<std::size_t>(y) * m_w;
        row.guideCentre = guides;
        for (int c = 0; c < 3; ++c) {
            row.centre[c] = m_row[c];
            for (int k = 0; k < kPostFilterTaps; ++k)
                row.tap[k][c] = m_row[c];
            row.out[c] = ringRow(it, y, c);
        }
        for (int k = 0; k < kPostFilterTaps; ++k)
            row.guideTap[k] = guides;
        filterPostFilterRow(row, m_g, m_w, m_horizontal[it], 1 << it);
    }

    /// Row y of iteration it's vertical half into the band's row (the last iteration: the
    /// output's row, interleaved).
    void verticalRow(int it, int y)
    {
        const int step = 1 << it;
        needHorizontal(it, std::min(y + 2 * step, m_h - 1));
        PostFilterRow row {};
        row.guideCentre = static_cast<std::size_t>(y) * m_w;
        for (int k = 0; k < kPostFilterTaps; ++k) {
            const int q = std::clamp(y + m_vertical[it][k].dy, 0, m_h - 1);
            row.guideTap[k] = static_cast<std::size_t>(q) * m_w;
            for (int c = 0; c < 3; ++c)
                row.tap[k][c] = ringRow(it, q, c);
        }
        for (int c = 0; c < 3; ++c)
            row.centre[c] = ringRow(it, y, c);
        if (it + 1 == kPostFilterIterations)
            row.interleaved = m_out.at(0, y);
        else
            for (int c = 0; c < 3; ++c)
                row.out[c] = m_row[c];
        filterPostFilterRow(row, m_g, m_w, m_vertical[it], step);
    }

    const Image& m_radiance;
    const PostFilterGuidePlanes& m_g;
    int m_w, m_h;
    Image& m_out;
    float* m_row[3];
    float* m_ringBase[kPostFilterIterations];
    int m_next[kPostFilterIterations];
    PostFilterTap m_horizontal[kPostFilterIterations][kPostFilterTaps];
    PostFilterTap m_vertical[kPostFilterIterations][kPostFilterTaps];
};

/// One band per thread, none shorter than kMinBandRows rows: each band also computes the halo
/// rows of the earlier half-passes (bandHalo: 14 + 12 + 8 rows), about 10 % more work for bands
/// of 180 rows. Two bands per thread (to even out threads the system runs unevenly) measured
/// slower at 720p on 2 threads (docs/performance.md).
constexpr int kMinBandRows = 64;

} // namespace

void edgeAwarePostFilter(const Image& radiance, const PostFilterGuides& guides,
    PostFilterWorkspace& workspace, Image& out)
{
    const int w = radiance.width(), h = radiance.height();
    out.resize(w, h, 3);
    if (w == 0 || h == 0)
        return;
    const std::size_t n = static_cast<std::size_t>(w) * h;
    const int threads = std::max(1, tbb::this_task_arena::max_concurrency());
    const int bands = std::clamp(h / kMinBandRows, 1, threads);
    // The workspace: the 9 guide planes, then the bands' rows; the noise scale's two scratch
    // planes are free once it is done, so the bands' rows reuse them.
    const std::size_t pitch = n + kPostFilterPlaneStagger;
    const std::size_t bandFloats = 3 * static_cast<std::size_t>(bandRows()) * bandPitch(w);
    workspace.storage.resize(9 * pitch + std::max(2 * pitch, bands * bandFloats));
    float* planes[9];
    for (int k = 0; k < 9; ++k)
        planes[k] = workspace.storage.data() + static_cast<std::size_t>(k) * pitch;
    float* const rest = workspace.storage.data() + 9 * pitch;
    const PostFilterGuidePlanes g { planes[0], planes[1], planes[2], planes[3], planes[4],
        planes[5], planes[6], planes[7], planes[8] };
    buildPostFilterGuidePlanes(guides, w, h, g);
    postFilterLuminanceScale(
        guides.noise, w, h, kPostFilterSigmaLuminance, rest, rest + pitch, g.ls);
    parallelFor(bands, [&](int band) {
        BandPasses passes(radiance, g, rest + static_cast<std::size_t>(band) * bandFloats, out);
        passes.run(static_cast<int>(static_cast<long>(h) * band / bands),
            static_cast<int>(static_cast<long>(h) * (band + 1) / bands));
    });
}

} // namespace afn::afnet
