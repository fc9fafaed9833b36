// SPDX-License-Identifier: Apache-2.0
// The afn engine's part of --benchmark:size: achieved GFLOP/s per network stage (from the filter's
// "stats.afn.*" statistics, afn.h) beside the machine's GEMM rate at 1 thread and at the run's
// thread count, measured in the same run: dnnl_sgemm (sgemm_peak.h) and oneDNN's bf16 matmul
// (bf16_gemm_peak.h). Each stage's share is of the GEMM of the precision its convolutions ran in
// (stats.afn.precision; the filtering's softmax and taps are fp32 either way).
#pragma once

#include "json_writer.h"

#include <string>
#include <vector>

namespace afntool {

/// One network stage at one size: medians over the timed frames.
struct EngineStage {
    /// prediction | pred-convs (prediction without its input preparation: the same FLOP) |
    /// filtering | refinement | network (prediction + filtering + refinement)
    std::string name;
    double gflop = 0.0; ///< per frame
    double ms = 0.0; ///< median wall-clock ms per frame
    double gflops() const { return ms > 0.0 ? gflop / ms * 1e3 : 0.0; }
};

/// afn at one size.
struct EnginePoint {
    int width = 0, height = 0;
    bool avx512 = false; ///< the AVX-512 kernels ran (else the portable ones)
    bool amx = false; ///< the bf16 convolutions ran on AMX tiles
    int precisionBits = 32; ///< what the convolutions ran in: 32 (fp32) or 16 (bf16)
    std::vector<EngineStage> stages;
};

/// The yardstick: dnnl_sgemm at 1 thread and at the run's thread count (absent without oneDNN).
struct EngineYardstick {
    bool available = false;
    int threads = 0; ///< the run's thread count
    double peak1 = 0.0, median1 = 0.0; ///< GFLOP/s on 1 thread: fastest and median call
    double peakN = 0.0, medianN = 0.0; ///< on `threads` threads
    int n = 0; ///< M = N = K
    /// oneDNN's bf16 matmul (bf16 inputs, fp32 sums), the same sizes and thread counts.
    bool bf16Available = false;
    std::string bf16Why; ///< why there is no bf16 rate (bf16Available false with oneDNN)
    double bf16Peak1 = 0.0, bf16Median1 = 0.0, bf16PeakN = 0.0, bf16MedianN = 0.0;
    /// The best `threads`-thread rate of the GEMM of `precisionBits` (0: not measured).
    double peakFor(int precisionBits) const
    {
        return precisionBits == 16 ? (bf16Available ? bf16PeakN : 0.0) : peakN;
    }
};

/// Collects afn's per-frame stage statistics (call add() after each timed frame).
class EngineCollector {
public:
    /// `stat(name)` reads a filter statistic (afnGetFilterFloat).
    template <typename Stat> void add(Stat&& stat)
    {
        static const char* names[] = { "prediction", "filtering", "refinement" };
        for (int k = 0; k < 3; ++k) {
            const std::string base = std::string("stats.afn.") + names[k];
            m_ms[k].push_back(stat((base + ".ms").c_str()));
            m_gflop[k] = stat((base + ".gflop").c_str());
        }
        m_inputMs.push_back(stat("stats.afn.prediction.inputMs"));
        m_avx512 = stat("stats.afn.avx512") != 0.0;
        m_amx = stat("stats.afn.bf16Amx") != 0.0;
        m_precisionBits = stat("stats.afn.precision") == 16.0 ? 16 : 32;
    }
    EnginePoint finish(int width, int height) const;

private:
    std::vector<double> m_ms[3];
    std::vector<double> m_inputMs; ///< of the prediction's ms, the input preparation's
    double m_gflop[3] = {};
    bool m_avx512 = false;
    bool m_amx = false;
    int m_precisionBits = 32;
};

/// Measure the yardstick (oneDNN threads: 1 and `threads`, 0 = all hardware threads).
EngineYardstick measureYardstick(int threads);

/// Text table of every point against the yardstick.
void printEngineReport(const EngineYardstick& y, const std::vector<EnginePoint>& points);

/// "engine": { "sgemm": {...}, "points": [...] } into an open JSON object.
void writeEngineJson(
    JsonWriter& j, const EngineYardstick& y, const std::vector<EnginePoint>& points);

/// engine.csv: one row per size and stage.
std::string engineCsv(const EngineYardstick& y, const std::vector<EnginePoint>& points);

} // namespace afntool
