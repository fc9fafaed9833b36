// SPDX-License-Identifier: Apache-2.0
// The afn engine report of --benchmark:size (see engine_report.h).
#include "engine_report.h"

#include "report.h"

#ifdef AFN_HAS_DNNL
#include "bf16_gemm_peak.h"
#include "sgemm_peak.h"
#endif

#include <cstdio>
#include <thread>

namespace afntool {

namespace {

// Why a stage stays below the GEMM rate (the report's last column; measured in
// docs/performance.md).
constexpr const char* kFilteringWhy
    = "about a third of its time is the softmax's 49 exponentials per pixel, which are not "
      "counted as FLOP; the 7x7 x 3-channel filters have weights that differ per pixel (2 FLOP "
      "per value loaded; no reuse); its two 1x1 heads compute 64 output channels in 16-wide "
      "vectors for the 49 and 50 needed";
constexpr const char* kPredictionWhy
    = "includes its input preparation (tone map; 13-channel input over the stripe windows; "
      "pooling) which does no FLOP: see pred-convs";

/// The report's "kernels": amx (the bf16 convolutions on AMX tiles, the rest AVX-512), avx512 or
/// portable.
const char* kernelsName(const EnginePoint& p)
{
    return p.amx ? "amx" : p.avx512 ? "avx512" : "portable";
}

/// The note of engine.csv for a stage (empty where the stage needs none).
const char* stageNote(const std::string& stage)
{
    if (stage == "filtering")
        return kFilteringWhy;
    if (stage == "prediction")
        return kPredictionWhy;
    if (stage == "network")
        return "prediction + filtering + refinement";
    return "";
}

} // namespace

EnginePoint EngineCollector::finish(int width, int height) const
{
    EnginePoint p;
    p.width = width, p.height = height, p.avx512 = m_avx512, p.amx = m_amx;
    p.precisionBits = m_precisionBits;
    static const char* names[] = { "prediction", "filtering", "refinement" };
    EngineStage total { "network" };
    for (int k = 0; k < 3; ++k) {
        EngineStage s { names[k], m_gflop[k], median(m_ms[k]) };
        total.gflop += s.gflop, total.ms += s.ms;
        p.stages.push_back(s);
        if (k == 0 && !m_inputMs.empty()) {
            // The prediction's convolutions alone: per frame its time less its input
            // preparation's (the median of the differences), the same FLOP.
            std::vector<double> convMs;
            for (std::size_t i = 0; i < m_ms[0].size() && i < m_inputMs.size(); ++i)
                if (m_inputMs[i] > 0.0)
                    convMs.push_back(m_ms[0][i] - m_inputMs[i]);
            if (!convMs.empty())
                p.stages.push_back({ "pred-convs", m_gflop[0], median(convMs) });
        }
    }
    p.stages.push_back(total);
    return p;
}

EngineYardstick measureYardstick(int threads)
{
    EngineYardstick y;
    y.threads = threads > 0 ? threads : static_cast<int>(std::thread::hardware_concurrency());
#ifdef AFN_HAS_DNNL
    const SgemmPeak one = measureSgemmPeak(1);
    const SgemmPeak all = measureSgemmPeak(y.threads);
    y.available = true;
    y.n = one.n;
    y.peak1 = one.bestGflops, y.median1 = one.medianGflops;
    y.peakN = all.bestGflops, y.medianN = all.medianGflops;
    const Bf16GemmPeak bf1 = measureBf16GemmPeak(1);
    const Bf16GemmPeak bfN = bf1.available ? measureBf16GemmPeak(y.threads) : bf1;
    y.bf16Available = bf1.available && bfN.available;
    y.bf16Why = bf1.available ? bfN.why : bf1.why;
    y.bf16Peak1 = bf1.rate.bestGflops, y.bf16Median1 = bf1.rate.medianGflops;
    y.bf16PeakN = bfN.rate.bestGflops, y.bf16MedianN = bfN.rate.medianGflops;
#endif
    return y;
}

void printEngineReport(const EngineYardstick& y, const std::vector<EnginePoint>& points)
{
    if (points.empty())
        return;
    if (y.available)
        std::printf("\nsgemm yardstick (oneDNN dnnl_sgemm, %d^3, fp32, best/median of 7 calls): "
                    "1 thread %.1f / %.1f GFLOP/s, %d threads %.1f / %.1f GFLOP/s\n",
            y.n, y.peak1, y.median1, y.threads, y.peakN, y.medianN);
    else
        std::printf("\nsgemm yardstick: not measured (afntool was built without oneDNN)\n");
    if (y.bf16Available)
        std::printf("bf16 yardstick (oneDNN matmul, bf16 inputs, fp32 sums, %d^3): 1 thread "
                    "%.1f / %.1f GFLOP/s, %d threads %.1f / %.1f GFLOP/s\n",
            y.n, y.bf16Peak1, y.bf16Median1, y.threads, y.bf16PeakN, y.bf16MedianN);
    else if (y.available)
        std::printf("bf16 yardstick: not measured (%s)\n", y.bf16Why.c_str());
    std::printf("%-11s %11s %-8s %-4s %11s %10s %9s %13s %13s\n", "afn stage", "size", "kernels",
        "prec", "GFLOP/frame", "ms/frame", "GFLOP/s", "% GEMM peak", "% N x 1-thr");
    for (const EnginePoint& p : points)
        for (const EngineStage& s : p.stages) {
            const bool bf16 = p.precisionBits == 16;
            const double peak = y.peakFor(p.precisionBits);
            const double ideal = (bf16 ? y.bf16Peak1 : y.peak1) * y.threads; // N x 1-thread
            char pct[32] = "-", pctIdeal[32] = "-";
            if (y.available && peak > 0.0)
                std::snprintf(pct, sizeof pct, "%.0f %%", 100.0 * s.gflops() / peak);
            if (y.available && ideal > 0.0)
                std::snprintf(pctIdeal, sizeof pctIdeal, "%.0f %%", 100.0 * s.gflops() / ideal);
            std::printf("%-11s %5dx%-5d %-8s %-4s %11.2f %10.2f %9.1f %13s %13s\n", s.name.c_str(),
                p.width, p.height, kernelsName(p), bf16 ? "bf16" : "fp32", s.gflop, s.ms,
                s.gflops(), pct, pctIdeal);
        }
    std::printf(
        "(afn stage times: median wall-clock ms of the timed frames, from the filter's "
        "stats.afn.*; %% of the best %d-thread GEMM call of this run in the precision the "
        "convolutions ran in (fp32: dnnl_sgemm; bf16: oneDNN's bf16 matmul), and of %d x its "
        "best 1-thread call: under glibc's malloc the multi-thread dnnl_sgemm falls short of "
        "N x its 1-thread rate, docs/performance.md)\n",
        y.threads, y.threads);
    std::printf("(pred-convs: the prediction stage less its input preparation, which does no FLOP: "
                "the tone map and the 13-channel input over each stripe's window with its halos, "
                "and the 1-spp colour's pooling; network = prediction + filtering + refinement)\n");
    std::printf("(filtering cannot reach the GEMM rate: %s)\n", kFilteringWhy);
}

void writeEngineJson(
    JsonWriter& j, const EngineYardstick& y, const std::vector<EnginePoint>& points)
{
    j.key("engine").beginObject();
    j.key("sgemm").beginObject().field("available", y.available).field("n", y.n);
    j.field("threads", y.threads).field("peak1Gflops", y.peak1).field("median1Gflops", y.median1);
    j.field("peakGflops", y.peakN).field("medianGflops", y.medianN).endObject();
    j.key("bf16Gemm").beginObject().field("available", y.bf16Available);
    if (!y.bf16Available)
        j.field("why", y.bf16Why);
    j.field("bf16Peak1Gflops", y.bf16Peak1).field("bf16Median1Gflops", y.bf16Median1);
    j.field("bf16PeakNGflops", y.bf16PeakN).field("bf16MedianNGflops", y.bf16MedianN).endObject();
    j.key("points").beginArray();
    for (const EnginePoint& p : points) {
        j.beginObject().field("width", p.width).field("height", p.height);
        j.field("kernels", kernelsName(p));
        j.field("precision", p.precisionBits == 16 ? "bf16" : "fp32");
        j.key("stages").beginArray();
        for (const EngineStage& s : p.stages) {
            j.beginObject().field("stage", s.name).field("gflopPerFrame", s.gflop);
            j.field("msPerFrame", s.ms).field("gflops", s.gflops());
            j.field("fractionOfSgemmPeak", y.peakN > 0.0 ? s.gflops() / y.peakN : 0.0);
            const double peak = y.peakFor(p.precisionBits);
            j.field("fractionOfGemmPeak", peak > 0.0 ? s.gflops() / peak : 0.0);
            j.field("note", stageNote(s.name)).endObject();
        }
        j.endArray().endObject();
    }
    j.endArray().endObject();
}

std::string engineCsv(const EngineYardstick& y, const std::vector<EnginePoint>& points)
{
    std::string csv = "stage,width,height,kernels,precision,gflopPerFrame,msPerFrame,gflops,"
                      "sgemmThreads,sgemmPeakGflops,sgemmPeak1Gflops,fractionOfSgemmPeak,"
                      "bf16PeakGflops,bf16Peak1Gflops,fractionOfGemmPeak,note\n";
    for (const EnginePoint& p : points)
        for (const EngineStage& s : p.stages) {
            const double peak = y.peakFor(p.precisionBits);
            char line[896];
            std::snprintf(line, sizeof line,
                "%s,%d,%d,%s,%s,%.4f,%.3f,%.2f,%d,%.2f,%.2f,%.4f,%.2f,%.2f,%.4f,\"%s\"\n",
                s.name.c_str(), p.width, p.height, kernelsName(p),
                p.precisionBits == 16 ? "bf16" : "fp32", s.gflop, s.ms, s.gflops(), y.threads,
                y.peakN, y.peak1, y.peakN > 0.0 ? s.gflops() / y.peakN : 0.0, y.bf16PeakN,
                y.bf16Peak1, peak > 0.0 ? s.gflops() / peak : 0.0, stageNote(s.name));
            csv += line;
        }
    return csv;
}

} // namespace afntool
