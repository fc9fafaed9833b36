// SPDX-License-Identifier: Apache-2.0
// --compare REF: metrics of the current beauty of every frame against its reference frame, printed
// per frame and as sequence means (text table, or JSON with --json). Metrics come from libafn.
#include "ops.h"

#include "cli_error.h"
#include "json_writer.h"
#include "progress.h"
#include "report.h"

#include <cmath>
#include <cstdio>

namespace afntool {

// ---- SequenceEvaluator --------------------------------------------------------------------------

SequenceEvaluator::SequenceEvaluator(int threads)
{
    m_device = afn::newDevice();
    if (!m_device)
        throw CliError("cannot create an afn device");
    m_device.set("numThreads", threads);
    m_device.commit();
    std::string message;
    if (m_device.getError(&message) != afn::Error::None)
        throw CliError("device: " + message);
}

FrameResult SequenceEvaluator::evaluate(int frame, const std::vector<float>& test,
    const std::vector<float>& reference, int width, int height, const std::string& file)
{
    FrameResult r;
    r.frame = frame;
    std::string message;
    if (!afn::computeMetrics(m_device, test.data(), reference.data(), width, height, 3, r.metrics)
        && m_device.getError(&message) != afn::Error::None)
        throw CliError("metrics: " + message, file);
    if (m_prevTest.size() == test.size() && m_prevRef.size() == reference.size()) {
        if (!afn::computeTemporalMetrics(m_device, m_prevTest.data(), test.data(), m_prevRef.data(),
                reference.data(), width, height, 3, r.temporal)
            && m_device.getError(&message) != afn::Error::None)
            throw CliError("temporal metrics: " + message, file);
        r.hasTemporal = true;
    }
    m_prevTest = test;
    m_prevRef = reference;
    return r;
}

// ---- SequenceComparer ---------------------------------------------------------------------------

struct SequenceComparer::Impl {
    RunContext& ctx;
    std::string pattern;
    SequenceEvaluator evaluator;
    std::vector<FrameResult> results;
    std::vector<std::string> testFiles, refFiles;
    Impl(RunContext& c, const std::string& p)
        : ctx(c)
        , pattern(p)
        , evaluator(c.options().threads)
    {
    }
};

SequenceComparer::SequenceComparer(RunContext& ctx, const Action& action)
{
    if (action.arg.empty())
        throw CliError("--compare needs a reference file or frame pattern");
    m_impl = std::make_unique<Impl>(ctx, action.arg);
}

SequenceComparer::~SequenceComparer() = default;

void SequenceComparer::process(const LoadedFrame& frame, Progress* progress)
{
    Impl& s = *m_impl;
    std::string refPath = s.pattern;
    if (afn::io::hasFramePattern(s.pattern)) {
        if (!frame.ref.numbered)
            throw CliError(
                "--compare has a frame pattern but the input is a single file", s.pattern);
        refPath = afn::io::expandFramePattern(s.pattern, frame.ref.frame);
    }
    const LoadedFrame ref = loadFrame(s.ctx, { refPath, frame.ref.frame }, false);
    for (const std::string& w : ref.images.mapping.warnings)
        warn(w + " (" + refPath + ")", s.ctx.options().quiet, progress);
    const afn::io::RoleImage& tc = frame.images.roles.at(afn::io::Role::Color);
    const afn::io::RoleImage& rc = ref.images.roles.at(afn::io::Role::Color);
    if (tc.width != rc.width || tc.height != rc.height)
        throw CliError("--compare: reference size " + std::to_string(rc.width) + "x"
                + std::to_string(rc.height) + " does not match the input "
                + std::to_string(tc.width) + "x" + std::to_string(tc.height),
            refPath);
    FrameResult r = s.evaluator.evaluate(
        frame.ref.frame, frame.beauty, ref.beauty, tc.width, tc.height, refPath);
    if (r.metrics.nonFiniteTest > 0)
        warn(std::to_string(r.metrics.nonFiniteTest)
                + " NaN/Inf values in the compared image: "
                  "its metrics are NaN ("
                + frame.ref.path + ")",
            s.ctx.options().quiet, progress);
    if (r.metrics.nonFiniteReference > 0)
        warn(std::to_string(r.metrics.nonFiniteReference)
                + " NaN/Inf values in the reference: "
                  "metrics are NaN ("
                + refPath + ")",
            s.ctx.options().quiet, progress);
    s.results.push_back(r);
    s.testFiles.push_back(frame.ref.path);
    s.refFiles.push_back(refPath);
}

namespace {

std::string cell(double v, const char* fmt)
{
    if (std::isnan(v))
        return "nan";
    if (std::isinf(v))
        return v > 0 ? "inf" : "-inf";
    char buf[32];
    std::snprintf(buf, sizeof buf, fmt, v);
    return buf;
}

} // namespace

void SequenceComparer::finish()
{
    const Impl& s = *m_impl;
    const std::map<std::string, double> means = sequenceMeans(s.results);
    if (s.ctx.options().json) {
        JsonWriter j;
        j.beginObject().field("reference", s.pattern);
        j.field("conventions",
            "docs/metrics.md (T(x) = clip(max(x,0)^(1/2.2),0,1); SMAPE linear, "
            "eps 1e-3; mean = mean of per-frame values; null = NaN or inf)");
        j.key("frames").beginArray();
        for (std::size_t i = 0; i < s.results.size(); ++i) {
            const FrameResult& f = s.results[i];
            j.beginObject().field("frame", f.frame).field("file", s.testFiles[i]);
            j.field("referenceFile", s.refFiles[i]);
            for (const MetricColumn& c : metricColumns())
                if (!c.temporal || f.hasTemporal)
                    j.field(c.name, c.get(f));
            j.field("nonFiniteTest", static_cast<long long>(f.metrics.nonFiniteTest));
            j.field("nonFiniteReference", static_cast<long long>(f.metrics.nonFiniteReference));
            j.endObject();
        }
        j.endArray();
        j.key("mean").beginObject();
        for (const auto& [k, v] : means)
            j.field(k, v);
        j.endObject().endObject();
        std::printf("%s\n", j.str().c_str());
        return;
    }
    // Text: the headline metrics; --json has every variant.
    const char* names[] = { "psnr", "ssim", "rmse", "smape", "tge" };
    std::printf("%-7s", "frame");
    for (const char* n : names)
        std::printf(" %12s", metricColumn(n).name);
    std::printf("\n");
    for (const FrameResult& f : s.results) {
        std::printf("%-7d", f.frame);
        for (const char* n : names) {
            const MetricColumn& c = metricColumn(n);
            std::printf(
                " %12s", c.temporal && !f.hasTemporal ? "-" : cell(c.get(f), "%.6g").c_str());
        }
        std::printf("\n");
    }
    std::printf("%-7s", "mean");
    for (const char* n : names)
        std::printf(" %12s", cell(means.at(n), "%.6g").c_str());
    std::printf("\n(PSNR/SSIM/RMSE on T(x) = clip(x^(1/2.2), 0, 1); SMAPE linear, eps 1e-3; "
                "tge = temporal-gradient error; see docs/metrics.md)\n");
}

} // namespace afntool
