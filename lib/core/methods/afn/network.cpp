// SPDX-License-Identifier: Apache-2.0
// The AFN inference graph (see methods/afn/network.h).
#include "methods/afn/network.h"

#include "base/exception.h"
#include "base/parallel.h"
#include "methods/afn/fusion.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <vector>

namespace afn::afnet {

namespace {

constexpr int kRefineChannels = 10; // T(i) 3, albedo 3, normal01 3, depth01 1

/// An optional 0/1 flag of the archive's metadata (absent = 0); anything else is refused.
bool metaFlag(const nn::WeightsArchive& a, const std::string& key)
{
    const std::string v = a.meta(key, "0");
    if (v != "0" && v != "1")
        throwInvalidArgument(
            "invalid or corrupted weights (" + a.source() + "): " + key + "='" + v + "' (0 or 1)");
    return v == "1";
}
} // namespace

void Network::setPrecision(nn::Precision p)
{
    if (m_variant == Variant::Large)
        p = nn::Precision::Fp32;
    for (nn::Conv* c : { &m_enc1, &m_enc2, &m_enc3, &m_dec2, &m_dec1, &m_head1, &m_headTa, &m_head4,
             &m_headG, &m_ref1, &m_ref2, &m_ref3 })
        c->setPrecision(p);
    m_precision = p;
}

void Network::load(const nn::WeightsArchive& a)
{
    m_loaded = false;
    m_precision = nn::Precision::Fp32;
    m_quarter = false;
    m_albedoTrust = false;
    m_head4 = nn::Conv {};
    m_headG = nn::Conv {};
    // The sample count it was trained at (validated where models are chosen: model_set.cpp).
    const long spp = std::strtol(a.meta("spp", "1").c_str(), nullptr, 10);
    m_trainedSpp = spp >= 1 && spp <= (1 << 20) ? static_cast<int>(spp) : 1;
    const std::string v = a.meta("variant", "full");
    if (v == "full")
        m_variant = Variant::Full;
    else if (v == "fusion")
        m_variant = Variant::Fusion;
    else if (v == "1spp")
        m_variant = Variant::OneSpp;
    else if (v == "ta")
        m_variant = Variant::Ta;
    else if (v == "large")
        m_variant = Variant::Large;
    else
        throwInvalidArgument(
            "invalid or corrupted weights (" + a.source() + "): unknown variant '" + v + "'");
    if (m_variant == Variant::Large) {
        m_large.load(a);
        m_loaded = true;
        return;
    }
    m_history = metaFlag(a, "history");
    if (m_history && m_variant != Variant::Full && m_variant != Variant::Fusion)
        throwInvalidArgument("invalid or corrupted weights (" + a.source()
            + "): the history input needs variant full or fusion");
    const int inputs = inputChannels();
    // Widths follow from the tensor shapes; each layer checks its input against its producer.
    m_enc1.load(a, "enc1", inputs);
    m_enc2.load(a, "enc2", m_enc1.outChannels());
    m_enc3.load(a, "enc3", m_enc2.outChannels());
    m_dec2.load(a, "dec2", m_enc3.outChannels() + m_enc2.outChannels());
    m_dec1.load(a, "dec1", m_dec2.outChannels() + m_enc1.outChannels());
    m_head1.load(a, "head1", m_dec1.outChannels(), kKernelTaps);
    m_headTa.load(a, "headTA", m_dec1.outChannels() + inputs, kKernelTaps + 1);
    for (const nn::Conv* c : { &m_enc1, &m_enc2, &m_enc3, &m_dec2, &m_dec1 })
        if (c->kernelSize() != 3)
            throwInvalidArgument("invalid or corrupted weights (" + a.source()
                + "): encoder/decoder layers must be 3x3");
    if (m_head1.kernelSize() != 1 || m_headTa.kernelSize() != 1)
        throwInvalidArgument(
            "invalid or corrupted weights (" + a.source() + "): heads must be 1x1");
    m_quarter = metaFlag(a, "quarter");
    if (m_quarter) {
        if (m_variant != Variant::Full && m_variant != Variant::Fusion)
            throwInvalidArgument("invalid or corrupted weights (" + a.source()
                + "): the quarter scale needs variant full or fusion");
        m_head4.load(a, "head4", m_dec2.outChannels(), kKernelTaps + 1);
        if (m_head4.kernelSize() != 1)
            throwInvalidArgument(
                "invalid or corrupted weights (" + a.source() + "): heads must be 1x1");
    }
    m_albedoTrust = metaFlag(a, "albedoTrust");
    if (m_albedoTrust) {
        if (m_variant != Variant::Full && m_variant != Variant::Fusion)
            throwInvalidArgument("invalid or corrupted weights (" + a.source()
                + "): the albedo trust needs variant full or fusion");
        m_headG.load(a, "headG", m_enc1.outChannels(), 1);
        if (m_headG.kernelSize() != 3)
            throwInvalidArgument(
                "invalid or corrupted weights (" + a.source() + "): headG must be 3x3");
    }
    if (m_variant == Variant::Full) {
        m_ref1.load(a, "ref1", kRefineChannels);
        m_ref2.load(a, "ref2", m_ref1.outChannels());
        m_ref3.load(a, "ref3", m_ref2.outChannels(), 3);
    }
    m_loaded = true;
}

const nn::Conv& Network::layer(Layer which) const
{
    switch (which) {
    case Layer::Enc1:
        return m_enc1;
    case Layer::Enc2:
        return m_enc2;
    case Layer::Enc3:
        return m_enc3;
    case Layer::Dec2:
        return m_dec2;
    case Layer::Dec1:
        return m_dec1;
    case Layer::Head1:
        return m_head1;
    case Layer::HeadTa:
        return m_headTa;
    case Layer::Ref1:
        return m_ref1;
    case Layer::Ref2:
        return m_ref2;
    case Layer::Ref3:
        break;
    }
    return m_ref3;
}

Inputs Network::checkInputs(const Inputs& given)
{
    if (!m_loaded)
        throwInvalidOperation("AFN: no weights loaded");
    Inputs in = given;
    if (m_variant == Variant::OneSpp || m_variant == Variant::Large) // large reads no TA
        in.colorTa = in.color1;
    if (m_variant == Variant::Ta)
        in.color1 = in.colorTa;
    if (!in.color1)
        throwInvalidArgument("AFN: input 0 missing or of the wrong shape");
    const int w = in.color1->width(), h = in.color1->height();
    const Image* all[]
        = { in.color1, in.colorTa, in.albedo, in.normal01, in.depth01, in.history01 };
    const int chans[] = { 3, 3, 3, 3, 1, 1 };
    for (int k = 0; k < (m_history ? 6 : 5); ++k)
        if (!all[k] || all[k]->width() != w || all[k]->height() != h
            || all[k]->channels() != chans[k])
            throwInvalidArgument(
                "AFN: input " + std::to_string(k) + " missing or of the wrong shape");
    m_width = w;
    m_height = h;
    return in;
}

void Network::toneMapNetworkInput(const float* in, float* out, int n) const
{
    if (m_precision == nn::Precision::Bf16)
        toneMapRunBf16(in, out, n);
    else
        toneMapRun(in, out, n);
}

void Network::fillInput(
    const Inputs& in, int y0, int y1, int origin, Image& x, Image& color1, Image& colorTa) const
{
    const int w = m_width, h = m_height, wp = x.width();
    thread_local std::vector<float> tone; // the row's two tone-mapped colours
    tone.resize(static_cast<std::size_t>(6) * w);
    const int nc = x.channels();
    // Pixel xx >= w of a padded row repeats pixel w - 1 (edge replication), as rows >= h repeat
    // row h - 1.
    auto replicate = [&](Image& img, int row) {
        const int c = img.channels();
        const float* last = img.at(w - 1, row);
        for (int xx = w; xx < wp; ++xx)
            std::copy(last, last + c, img.at(xx, row));
    };
    for (int y = y0; y < y1; ++y) {
        const int sy = std::min(y, h - 1); // edge replication
        const int row = y - origin;
        toneMapNetworkInput(in.color1->at(0, sy), tone.data(), 3 * w);
        toneMapNetworkInput(in.colorTa->at(0, sy), tone.data() + 3 * w, 3 * w);
        const float* ta = tone.data();
        const float* tb = tone.data() + 3 * w;
        const float* al = in.albedo->at(0, sy);
        const float* nm = in.normal01->at(0, sy);
        const float* dp = in.depth01->at(0, sy);
        const float* hist = m_history ? in.history01->at(0, sy) : nullptr;
        float* o = x.at(0, row);
        for (int xx = 0; xx < w; ++xx, o += nc) {
            for (int c = 0; c < 3; ++c) {
                o[c] = ta[3 * xx + c];
                o[3 + c] = tb[3 * xx + c];
                o[6 + c] = al[3 * xx + c];
                o[9 + c] = nm[3 * xx + c];
            }
            o[12] = dp[xx];
            if (hist)
                o[13] = hist[xx];
        }
        std::copy(in.color1->at(0, sy), in.color1->at(0, sy) + 3 * w, color1.at(0, row));
        std::copy(in.colorTa->at(0, sy), in.colorTa->at(0, sy) + 3 * w, colorTa.at(0, row));
        for (Image* img : { &x, &color1, &colorTa })
            replicate(*img, row);
    }
}

void Network::prepare(const Inputs& given)
{
    const Inputs in = checkInputs(given);
    if (m_variant == Variant::Large)
        throwInvalidOperation("AFN large runs whole (run, runWholeFrame), not by stages");
    const int wp = paddedSize(m_width), hp = paddedSize(m_height);
    m_x.resize(wp, hp, inputChannels());
    m_colorTa.resize(wp, hp, 3);
    m_color1.resize(wp, hp, 3);
    parallelRows(hp, [&](int y0, int y1) { fillInput(in, y0, y1, 0, m_x, m_color1, m_colorTa); });
    if (!m_albedoTrust) // else in predict(), once the colours are rescaled
        nn::down2(m_color1, m_color1Half);
}

void Network::predict()
{
    nn::down2(m_x, m_xHalf);
    m_enc1.run(nullptr, m_xHalf, m_e1, true);
    if (m_albedoTrust) { // albedo_trust.h: t, the rescaled colours, then D(r_1spp)
        m_trust.resize(m_e1.width(), m_e1.height(), 1);
        parallelRows(m_e1.height(),
            [&](int y0, int y1) { albedoTrustRows(m_headG, m_e1, y0, y1, m_trust); });
        parallelRows(m_x.height(), [&](int y0, int y1) {
            applyAlbedoTrustRows(m_x, m_trust, y0, y1, m_color1);
            applyAlbedoTrustRows(m_x, m_trust, y0, y1, m_colorTa);
        });
        nn::down2(m_color1, m_color1Half);
    }
    nn::down2(m_e1, m_e1Pool);
    m_enc2.run(nullptr, m_e1Pool, m_e2, true);
    nn::down2(m_e2, m_e2Pool);
    m_enc3.run(nullptr, m_e2Pool, m_e3, true);
    m_dec2.run(&m_e3, m_e2, m_d2, true);
    m_dec1.run(&m_d2, m_e1, m_d1, true);
}

void Network::filterAndFuse()
{
    FusionInputs in;
    in.d1 = &m_d1;
    in.x = &m_x;
    in.colorTa = &m_colorTa;
    in.color1Half = &m_color1Half;
    in.head1 = &m_head1;
    in.headTa = &m_headTa;
    FusionOutputs out;
    out.fused = &m_fused;
    out.filteredTa = &m_dTa;
    out.alpha = &m_alpha;
    out.filtered1Half = &m_d1Half;
    afnet::filterAndFuse(in, out);
    if (m_quarter)
        applyQuarterScale(m_head4, m_d2, m_fused, m_quarterBuf);
}

void Network::fusedToOutput(Image& out) const
{
    out.resize(m_width, m_height, 3);
    for (int y = 0; y < m_height; ++y)
        std::copy(m_fused.at(0, y), m_fused.at(0, y) + 3 * m_width, out.at(0, y));
    if (m_albedoTrust)
        parallelRows(m_height, [&](int y0, int y1) {
            undoAlbedoTrustRows(m_x, m_trust, y0, y1, m_width, out.at(0, y0), 3L * m_width);
        });
}

void Network::crop(Image& out) const
{
    out.resize(m_width, m_height, 3);
    for (int y = 0; y < m_height; ++y)
        std::copy(m_out.at(0, y), m_out.at(0, y) + 3 * m_width, out.at(0, y));
}

const char* Network::stageName(Stage s)
{
    return s == Stage::Prediction ? "prediction"
        : s == Stage::Filtering   ? "filtering"
                                  : "refinement";
}

double Network::stageFlop(Stage s) const
{
    if (m_variant == Variant::Large)
        return m_large.stageFlop(static_cast<int>(s));
    const double full = static_cast<double>(paddedSize(m_width)) * paddedSize(m_height);
    const double half = full / 4, quarter = full / 16, eighth = full / 64;
    switch (s) {
    case Stage::Prediction:
        return (m_albedoTrust ? m_headG.flopPerPixel() * half : 0.0) + m_enc1.flopPerPixel() * half
            + m_enc2.flopPerPixel() * quarter + m_enc3.flopPerPixel() * eighth
            + m_dec2.flopPerPixel() * quarter + m_dec1.flopPerPixel() * half;
    case Stage::Filtering: // heads + two 7x7 x 3-channel filters (half and full resolution)
        return m_head1.flopPerPixel() * half + m_headTa.flopPerPixel() * full
            + 2.0 * kKernelTaps * 3 * (full + half)
            + (m_quarter ? (m_head4.flopPerPixel() + 2.0 * kKernelTaps * 3) * quarter : 0.0);
    case Stage::Refinement:
        break;
    }
    return m_variant != Variant::Full
        ? 0.0
        : (m_ref1.flopPerPixel() + m_ref2.flopPerPixel() + m_ref3.flopPerPixel()) * full;
}

void Network::runWholeFrame(const Inputs& in, Image& out)
{
    using Clock = std::chrono::steady_clock;
    auto ms = [](Clock::time_point a, Clock::time_point b) {
        return std::chrono::duration<double, std::milli>(b - a).count();
    };
    if (m_variant == Variant::Large) {
        m_large.run(checkInputs(in), out, m_stageMs);
        m_inputMs = 0.0;
        return;
    }
    const Clock::time_point t0 = Clock::now();
    prepare(in);
    m_inputMs = ms(t0, Clock::now());
    predict();
    const Clock::time_point t1 = Clock::now();
    filterAndFuse();
    const Clock::time_point t2 = Clock::now();
    refine();
    const Clock::time_point t3 = Clock::now();
    crop(out);
    m_stageMs[0] = ms(t0, t1);
    m_stageMs[1] = ms(t1, t2);
    m_stageMs[2] = ms(t2, t3);
}

} // namespace afn::afnet
