// SPDX-License-Identifier: Apache-2.0
// afn's edge-aware post-filter (post_filter.h): the six half-passes row by row through small rings
// of rows (BandPasses), one band of the frame's rows per task, each row filtered by the row kernel
// (post_filter_row.h); the guides and the noise scale are made row by row into a ring as the
// passes first read them. So nothing of the frame's size is written between the input and the
// output, and the colour between half-passes stays in the processor's cache: half-passes that
// each crossed the whole frame were bound by memory traffic (docs/performance.md). The last
// half-pass writes the output interleaved.
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

/// Rows of a band's guide ring: the last vertical half at row y reads the guides of rows
/// y - 2 (1 << last) .. y + 2 (1 << last) while the first horizontal half is bandHalo(0) rows
/// ahead of y.
constexpr int kGuideRingRows = 2 * (1 << (kPostFilterIterations - 1)) + bandHalo(0) + 1;
constexpr int kGuidePlanes = 9;

/// Floats of a band's row of one plane: the width and a cache line, so that the rows' planes
/// start at different offsets within a page.
std::size_t bandPitch(int w)
{
    return static_cast<std::size_t>(w) + kPostFilterPlaneStagger;
}

/// Floats between one guide plane's ring and the next one's.
std::size_t guidePlanePitch(int w)
{
    return kGuideRingRows * bandPitch(w) + kPostFilterPlaneStagger;
}

/// Floats of one band's storage: its colour rows, its guide rings and the noise scale's rows.
std::size_t bandFloats(int w)
{
    return 3 * static_cast<std::size_t>(bandRows()) * bandPitch(w)
        + kGuidePlanes * guidePlanePitch(w) + PostFilterNoiseRows::storageFloats(w);
}

/// The passes of the rows of one band of the frame, row by row: every half-pass row is computed
/// when the next half-pass first reads it, into a small ring of rows, so the colour stays in the
/// processor's cache between the six half-passes instead of crossing memory six times; the
/// guides likewise. A band computes the rows of the earlier half-passes its first rows read
/// before them (bandHalo), as the band above computes them too: the same values, as each row is
/// the same computation.
class BandPasses {
public:
    BandPasses(const Image& radiance, const PostFilterGuides& guides, float* storage, Image& out)
        : m_radiance(radiance)
        , m_guides(guides)
        , m_w(radiance.width())
        , m_h(radiance.height())
        , m_out(out)
        , m_noise(guides.noise, m_w, m_h, kPostFilterSigmaLuminance,
              storage + bandFloats(m_w) - PostFilterNoiseRows::storageFloats(m_w))
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
        float* planes[kGuidePlanes];
        for (float*& plane : planes) {
            plane = next;
            next += guidePlanePitch(m_w);
        }
        m_g = { planes[0], planes[1], planes[2], planes[3], planes[4], planes[5], planes[6],
            planes[7], planes[8] };
    }

    /// Output rows [y0, y1).
    void run(int y0, int y1)
    {
        for (int it = 0; it < kPostFilterIterations; ++it)
            m_next[it] = std::max(0, y0 - bandHalo(it));
        m_nextGuide = m_next[0];
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

    /// Where row y's guides start in each guide plane.
    std::size_t guideRow(int y) const
    {
        return static_cast<std::size_t>(y % kGuideRingRows) * bandPitch(m_w);
    }

    /// Makes the guide rows up to `last`.
    void needGuides(int last)
    {
        for (; m_nextGuide <= last; ++m_nextGuide) {
            const std::size_t o = guideRow(m_nextGuide);
            buildPostFilterGuideRow(m_guides, m_w, m_h, m_nextGuide, m_g, o);
            m_noise.row(m_nextGuide, m_g.ls + o);
        }
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
        if (it == 0) {
            needGuides(y);
            cpu::deinterleaveRgbRow(m_radiance.at(0, y), m_row[0], m_row[1], m_row[2], m_w);
        } else {
            verticalRow(it - 1, y);
        }
        PostFilterRow row {};
        const std::size_t guides = guideRow(y);
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
        row.guideCentre = guideRow(y);
        for (int k = 0; k < kPostFilterTaps; ++k) {
            const int q = std::clamp(y + m_vertical[it][k].dy, 0, m_h - 1);
            row.guideTap[k] = guideRow(q);
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
    const PostFilterGuides& m_guides;
    int m_w, m_h;
    Image& m_out;
    PostFilterNoiseRows m_noise;
    PostFilterGuidePlanes m_g; ///< the guide rings
    int m_nextGuide = 0;
    float* m_row[3];
    float* m_ringBase[kPostFilterIterations];
    int m_next[kPostFilterIterations];
    PostFilterTap m_horizontal[kPostFilterIterations][kPostFilterTaps];
    PostFilterTap m_vertical[kPostFilterIterations][kPostFilterTaps];
};

/// One band per thread, none shorter than kMinBandRows rows: each band also computes the halo
/// rows of the earlier half-passes (bandHalo: 14 + 12 + 8 rows above and below it), 2.5 % more
/// half-pass rows for two bands of 360 rows, 7.5 % for four of 180. Two bands per thread (to
/// even out threads the system runs unevenly) measured slower at 720p on 2 threads
/// (docs/experiments.md).
constexpr int kMinBandRows = 64;

} // namespace

void edgeAwarePostFilter(const Image& radiance, const PostFilterGuides& guides,
    PostFilterWorkspace& workspace, Image& out)
{
    const int w = radiance.width(), h = radiance.height();
    out.resize(w, h, 3);
    if (w == 0 || h == 0)
        return;
    const int threads = std::max(1, tbb::this_task_arena::max_concurrency());
    const int bands = std::clamp(h / kMinBandRows, 1, threads);
    const std::size_t perBand = bandFloats(w);
    workspace.storage.resize(static_cast<std::size_t>(bands) * perBand);
    parallelFor(bands, [&](int band) {
        BandPasses passes(radiance, guides,
            workspace.storage.data() + static_cast<std::size_t>(band) * perBand, out);
        passes.run(static_cast<int>(static_cast<long>(h) * band / bands),
            static_cast<int>(static_cast<long>(h) * (band + 1) / bands));
    });
}

} // namespace afn::afnet
