// SPDX-License-Identifier: Apache-2.0
#include "ops.h"

#include "arg_checks.h"
#include "cli_error.h"
#include "info_afn_model.h"
#include "near_match.h"
#include "output_header.h"
#include "progress.h"
#include "sample_count.h"
#include "text.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>

#include <iostream>

namespace afntool {

using afn::io::Role;

namespace {

/// A note on stderr, once per run (benchmarks create many denoisers).
void noteOnce(const std::string& text, bool quiet)
{
    static bool said = false;
    if (!quiet && !said)
        std::cerr << "afntool: note: " << text << "\n";
    said = true;
}

} // namespace

void SequenceDenoiser::openOnCuda(const std::string& choice)
{
    afn::DeviceRef cuda = afn::newDevice(afn::DeviceType::CUDA);
    if (!cuda) {
        const char* why = nullptr;
        afnGetDeviceError(nullptr, &why);
        const std::string reason = why ? why : "unknown reason";
        if (choice == "cuda")
            throw CliError("--device cuda: " + reason);
        noteOnce("no CUDA device (" + reason + "); denoising on the CPU", m_opts.quiet);
        return;
    }
    cuda.set("numThreads", m_opts.threads);
    cuda.commit();
    afn::FilterRef filter = cuda.newFilter(m_method.c_str());
    std::string message;
    const afn::Error error = cuda.getError(&message);
    if (error == afn::Error::None) {
        m_device = cuda;
        m_filter = filter;
    } else if (choice == "auto" && error == afn::Error::Unsupported) {
        noteOnce(
            "method '" + m_method + "' runs on the CPU only; denoising on the CPU", m_opts.quiet);
    } else {
        throw CliError(m_flag + ": " + message);
    }
}

SequenceDenoiser::SequenceDenoiser(const Options& opts, const Action& action)
    : m_opts(opts)
    , m_flag("--" + action.name)
    , m_features(action.name == "features")
{
    m_params = action.mods;
    auto it = m_params.find("method");
    if (it == m_params.end() && !m_features)
        throw CliError("--denoise needs :method=NAME (see afntool --methods)");
    m_method = it == m_params.end() ? "afn" : it->second;
    if (it != m_params.end())
        m_params.erase(it);
    checkMethodName(m_flag, m_method);
    checkMethodParameters(m_flag, m_method, m_params, { "weights", "mask", "passes" });
    if (auto ps = m_params.find("passes"); ps != m_params.end()) {
        m_passes = ps->second;
        m_params.erase(ps);
        if (m_passes.empty())
            throw CliError(
                m_flag + ": :passes= needs all, none or pass names (see afntool --info)");
        if (m_features && m_passes != "none")
            throw CliError("--features does not denoise passes (:passes=)");
        if (m_passes != "none" && !opts.keepAovs)
            warn(m_flag
                    + ": :passes= denoises the light passes, but only --keep-aovs writes them "
                      "into -o outputs",
                opts.quiet, nullptr);
    }
    if (auto mk = m_params.find("mask"); mk != m_params.end()) {
        m_maskChannel = mk->second;
        m_params.erase(mk);
        if (m_maskChannel.empty())
            throw CliError(m_flag + ": :mask= needs a channel name (e.g. :mask=matte.R)");
    }
    // Feature outputs are computed on the CPU: auto stays there, cuda reports the device's error.
    if (opts.device == "cuda" || (opts.device == "auto" && !m_features))
        openOnCuda(opts.device);
    if (!m_filter) {
        m_device = afn::newDevice(afn::DeviceType::CPU);
        if (!m_device)
            throw CliError("cannot create an afn device");
        m_device.set("numThreads", opts.threads);
        m_device.commit();
        check("device", "");
        m_filter = m_device.newFilter(m_method.c_str());
        check(m_flag, "");
    }
    if (m_features && afn::filterTypeFeatures(m_method.c_str()).empty())
        throw CliError("--features: method '" + m_method + "' has no feature outputs");
    for (const AFNParamInfo& p : afn::filterTypeParams(m_method.c_str())) {
        m_hasSpp = m_hasSpp || std::string(p.name) == AFN_PARAM_SPP;
        m_hasAux = m_hasAux || std::string(p.name) == AFN_PARAM_AUX;
    }

    // Weights: ":weights=FILE" on this action, else --weights FILE; read once, handed over as data.
    std::string weights = opts.weights;
    if (auto w = m_params.find("weights"); w != m_params.end()) {
        weights = w->second;
        m_params.erase(w);
    }
    m_weights = weights;
    if (!weights.empty()) {
        std::vector<char> data;
        if (!afn::readFile(weights, data))
            throw CliError("cannot read the weights file", weights);
        m_filter.setData(AFN_DATA_WEIGHTS, data.data(), data.size()); // the library copies them
        check("--weights (" + weights + ")", "");
    }
}

void SequenceDenoiser::check(const std::string& what, const std::string& file)
{
    std::string message;
    if (m_device.getError(&message) != afn::Error::None)
        throw CliError(what + ": " + message, file);
}

namespace {

/// "3.21 %" for a speckle share, "-" without the input.
std::string shareText(float share)
{
    if (share < 0.0f)
        return "-";
    char text[32];
    std::snprintf(text, sizeof(text), "%.2f %%", 100.0 * share);
    return text;
}

afn::Format formatFor(int components)
{
    switch (components) {
    case 1:
        return afn::Format::Float;
    case 2:
        return afn::Format::Float2;
    case 3:
        return afn::Format::Float3;
    default:
        return afn::Format::Float4;
    }
}

} // namespace

void SequenceDenoiser::run(LoadedFrame& frame, Progress* progress)
{
    afn::io::FrameImages& img = frame.images;
    const afn::io::RoleImage& color = img.roles.at(Role::Color);
    const int w = color.width, h = color.height;

    // Conventions of this file's AOVs, then the user's explicit parameters (which win).
    for (const auto& [name, value] : img.mapping.tag.parameters())
        m_filter.set(name.c_str(), value);
    if (const std::optional<int> spp = sampleCountParam(m_hasSpp, m_params, img.samples))
        m_filter.set(
            AFN_PARAM_SPP, *spp); // the sample count in the file's header, 0 when it has none
    for (const auto& [key, value] : m_params)
        m_filter.set(key.c_str(), value);
    check(m_flag, frame.ref.path);

    // The working-space beauty is the colour input; other roles as read.
    m_filter.setImage(AFN_IMAGE_COLOR, frame.beauty.data(), afn::Format::Float3, w, h);
    const std::pair<Role, const char*> roles[]
        = { { Role::Albedo, AFN_IMAGE_ALBEDO }, { Role::Normal, AFN_IMAGE_NORMAL },
              { Role::Depth, AFN_IMAGE_DEPTH }, { Role::Position, AFN_IMAGE_POSITION },
              { Role::Motion, AFN_IMAGE_MOTION }, { Role::Alpha, AFN_IMAGE_ALPHA } };
    for (const auto& [role, name] : roles) {
        auto it = img.roles.find(role);
        if (it == img.roles.end()) {
            m_filter.unsetImage(name);
            continue;
        }
        afn::io::RoleImage& r = it->second;
        m_filter.setImage(name, r.pixels.data(), formatFor(r.components), r.width, r.height, 0,
            r.components * sizeof(float), 0);
    }
    bindMask(frame);
    bindPasses(frame, progress);
    if (img.camera) {
        m_filter.setFloats(AFN_ARRAY_VIEW_PROJECTION, img.camera->viewProjection, 16);
        m_filter.setFloats(AFN_ARRAY_PIXEL_OFFSET, img.camera->pixelOffset, 2);
    }
    if (m_features) {
        // Every feature output, packed side by side in one buffer; no "output": the method
        // stops once its features are written.
        const std::vector<AFNFeatureInfo> features = afn::filterTypeFeatures(m_method.c_str());
        int channels = 0;
        for (const AFNFeatureInfo& f : features)
            channels += f.channels;
        m_output.assign(static_cast<std::size_t>(w) * h * channels, 0.0f);
        int offset = 0;
        for (const AFNFeatureInfo& f : features) {
            m_filter.setImage((std::string(AFN_IMAGE_FEATURE_PREFIX) + f.name).c_str(),
                m_output.data(), formatFor(f.channels), w, h, offset * sizeof(float),
                channels * sizeof(float), 0);
            offset += f.channels;
        }
    } else {
        // The filter writes every pixel of "output": no fill pass over a buffer of this size.
        m_output.resize(static_cast<std::size_t>(w) * h * 3);
        m_filter.setImage(AFN_IMAGE_OUTPUT, m_output.data(), afn::Format::Float3, w, h);
    }
    m_filter.commit();
    check(m_flag, frame.ref.path);
    m_filter.execute();
    check(m_flag, frame.ref.path);

    logFrame(frame, progress);
    const int nonFinite = m_filter.get<int>(AFN_STAT_NON_FINITE);
    const int negative = m_filter.get<int>(AFN_STAT_NEGATIVE);
    if (nonFinite > 0)
        warn(std::to_string(nonFinite) + " NaN/Inf input values replaced by 0 (" + frame.ref.path
                + ")",
            m_opts.quiet, progress);
    if (negative > 0)
        warn(std::to_string(negative) + " negative colour values clamped to 0 (" + frame.ref.path
                + ")",
            m_opts.quiet, progress);
}

void SequenceDenoiser::bindMask(const LoadedFrame& frame)
{
    if (m_maskChannel.empty()) {
        m_filter.unsetImage(AFN_IMAGE_MASK);
        return;
    }
    const std::optional<afn::io::LayeredImage>& all = frame.images.all;
    const auto& names = all ? all->channels : std::vector<std::string> {};
    const auto it = std::find(names.begin(), names.end(), m_maskChannel);
    if (!all || it == names.end()) {
        std::string list;
        for (const std::string& n : names)
            list += (list.empty() ? "" : ", ") + n;
        throw CliError(m_flag + ": mask channel '" + m_maskChannel + "' is not in the file"
                + didYouMean(m_maskChannel, names) + " (channels: " + list + ")",
            frame.ref.path);
    }
    const std::size_t stride = names.size(), c = it - names.begin();
    const std::size_t n = static_cast<std::size_t>(all->width) * all->height;
    m_mask.resize(n);
    for (std::size_t i = 0; i < n; ++i)
        m_mask[i] = all->pixels[i * stride + c];
    m_filter.setImage(AFN_IMAGE_MASK, m_mask.data(), afn::Format::Float, all->width, all->height);
}

namespace {

/// "a; b; c" of the non-empty items.
std::string joinFacts(const std::vector<std::string>& items)
{
    std::string text;
    for (const std::string& item : items)
        if (!item.empty())
            text += (text.empty() ? "" : "; ") + item;
    return text;
}

} // namespace

void SequenceDenoiser::logFrame(const LoadedFrame& frame, Progress* progress)
{
    const bool quiet = m_opts.quiet;
    // Inputs the method reads but the file does not have: warned about clearly (once, and again
    // when it changes).
    const std::string missing = m_filter.get<std::string>(AFN_STAT_MISSING_INPUTS);
    if (!missing.empty() && missing != m_missingWarned)
        warn(m_flag + ": " + m_method + " runs without " + missing
                + ". Map the AOVs with --aov ROLE=CHANNELS (see afntool --info " + frame.ref.path
                + ")",
            quiet, progress);
    m_missingWarned = missing;
    std::string missingShort;
    for (const std::string& item : splitList(missing, ';')) {
        const std::string name = item.substr(item.find_first_not_of(' '));
        missingShort += (missingShort.empty() ? "" : ", ") + name.substr(0, name.find(" ("));
    }

    // What the run is doing (said on the first frame and again when it changes) and the figures
    // that vary from frame to frame (the first frame's, and every frame's with -v).
    std::string model, network, aux, speckle, skippedText;
    if (m_method == "afn") {
        // The network's arithmetic (precision=auto|fp32|bf16, chosen from the CPU).
        network = "network " + networkArithmetic(m_filter);
        // The trained model chosen for the file's inputs; one for fewer inputs than the file has
        // is warned about (once per change).
        model = m_filter.get<std::string>(AFN_STAT_AFN_MODEL);
        if (model.find("not used:") != std::string::npos && model != m_modelWarned)
            warn(m_flag + ": afn has no model for all of the file's inputs and runs " + model,
                quiet, progress);
        m_modelWarned = model;
    }
    if (m_hasAux) { // the method demodulates
        const std::string mode = m_filter.get<std::string>(AFN_PARAM_AUX);
        const bool noisy = m_filter.get<bool>(AFN_STAT_AUX_NOISY);
        // The sample count takes part in aux=auto's decision (stages/aux_prefilter.h): say it.
        const int spp = m_hasSpp ? m_filter.get<int>(AFN_PARAM_SPP) : 0;
        const std::string sppText = spp > 0 ? ", " + std::to_string(spp) + " spp" : "";
        const bool grain = m_filter.get<bool>(AFN_STAT_AUX_GRAIN_LIMITED);
        aux = std::string("aux ")
            + (noisy        ? "noisy"
                    : grain ? "clean, albedo grain limited"
                            : "clean")
            + " (aux=" + mode + sppText;
        // Asked for only where printed (the first frame, or every frame with -v): the library
        // measures a clean history's shares when asked, not on every frame.
        if (m_opts.verbose || !m_factsLogged)
            speckle = "speckle: albedo " + shareText(m_filter.get<float>(AFN_STAT_ALBEDO_SPECKLE))
                + ", normal " + shareText(m_filter.get<float>(AFN_STAT_NORMAL_SPECKLE)) + ", depth "
                + shareText(m_filter.get<float>(AFN_STAT_DEPTH_SPECKLE));
    }
    const float skipped = m_filter.get<float>(AFN_STAT_SKIPPED);
    if (skipped > 0.0f)
        skippedText = "skipped " + shareText(skipped) + " of the pixels (background, alpha 0"
            + (m_maskChannel.empty() ? "" : ", mask") + "; skip=off filters them)";

    // The share of pixels whose history a change of the lighting cut (stages/history_trust.h):
    // on the frame's own line, when there is one.
    const float cut = m_filter.get<float>(AFN_STAT_HISTORY_CUT);
    const std::string cutText = cut >= 0.0005f ? "history cut " + shareText(cut) : "";
    if (!cutText.empty() && progress)
        progress->annotate(cutText);

    if (m_opts.verbose) { // every frame, every figure
        // Highlights kept at their pixel instead of filtered (stages/highlight_bypass.h).
        const auto highlights = static_cast<long long>(m_filter.get<float>(AFN_STAT_HIGHLIGHTS));
        if (highlights > 0)
            note(m_flag + ": " + m_method + " kept " + std::to_string(highlights)
                    + " highlight px unfiltered (highlights) " + frame.ref.path,
                quiet, progress);
        if (!cutText.empty())
            note(m_flag + ": " + m_method + " " + cutText + " (lighting changed) " + frame.ref.path,
                quiet, progress);
        // The detail restoration (stages/detail_restore.h), where it ran.
        const float restored = m_filter.get<float>(AFN_STAT_RESTORED);
        if (restored >= 0.0005f)
            note(m_flag + ": " + m_method + " restored detail on " + shareText(restored)
                    + " of the pixels (restore) " + frame.ref.path,
                quiet, progress);
        if (!missingShort.empty())
            note(m_flag + ": " + m_method + " without " + missingShort + " " + frame.ref.path,
                quiet, progress);
        if (!model.empty())
            note(m_flag + ": afn " + model + " " + frame.ref.path, quiet, progress);
        if (!aux.empty())
            note(m_flag + ": " + aux + "; " + speckle + ") " + frame.ref.path, quiet, progress);
        if (!skippedText.empty())
            note(m_flag + ": " + m_method + " " + skippedText + " " + frame.ref.path, quiet,
                progress);
        return;
    }
    const std::string facts = joinFacts({ missingShort.empty() ? "" : "without " + missingShort,
        model, network, aux.empty() ? "" : aux + ")" });
    if (!m_factsLogged) {
        // The missing inputs are in the warning above: not repeated here.
        const std::string first = joinFacts(
            { model, network, aux.empty() ? "" : aux + "; " + speckle + ")", skippedText });
        if (!first.empty())
            note(m_flag + ": " + m_method + " " + first, quiet, progress);
    } else if (facts != *m_factsLogged) {
        note(m_flag + ": " + m_method + " now " + facts + " " + frame.ref.path, quiet, progress);
    }
    m_factsLogged = facts;
}

std::string SequenceDenoiser::describe() const
{
    std::string text = m_flag + ":method=" + m_method;
    for (const AFNParamInfo& p : afn::filterTypeParams(m_method.c_str())) {
        std::string value;
        switch (p.type) {
        case AFN_PARAM_BOOL:
            value = m_filter.get<bool>(p.name) ? "1" : "0";
            break;
        case AFN_PARAM_INT:
            value = std::to_string(m_filter.get<int>(p.name));
            break;
        case AFN_PARAM_FLOAT: {
            // The shortest text that reads back as the same float (0.2, not 0.200000003).
            const float v = m_filter.get<float>(p.name);
            char buf[32];
            for (int digits = 6; digits <= 9; ++digits) {
                std::snprintf(buf, sizeof buf, "%.*g", digits, v);
                if (std::strtof(buf, nullptr) == v)
                    break;
            }
            value = buf;
            break;
        }
        case AFN_PARAM_STRING:
            value = m_filter.get<std::string>(p.name);
            break;
        }
        text += std::string(":") + p.name + "=" + value;
    }
    if (!m_weights.empty())
        text += ":weights=" + m_weights;
    if (!m_passesBound.empty()) {
        // Which light passes were denoised with the beauty (Exif:ImageHistory).
        text += ":passes=";
        for (std::size_t i = 0; i < m_passesBound.size(); ++i)
            text += (i ? "," : "") + m_passesBound[i];
    }
    return text;
}

void SequenceDenoiser::process(LoadedFrame& frame, Progress* progress)
{
    run(frame, progress);
    frame.beauty.swap(m_output);
    frame.history.push_back(describe());
    for (const std::string& name : m_passesBound)
        frame.denoisedPasses.insert(name);
}

void SequenceDenoiser::writeFeatures(LoadedFrame& frame, const std::string& path,
    const std::vector<std::string>& inputs, Progress* progress)
{
    run(frame, progress);
    std::vector<std::string> channels;
    for (const AFNFeatureInfo& f : afn::filterTypeFeatures(m_method.c_str())) {
        static const char* const kRgb[] = { "R", "G", "B" };
        for (int c = 0; c < f.channels; ++c)
            channels.push_back(std::string(f.name) + "." + (f.channels == 1 ? "Z" : kRgb[c]));
    }
    const afn::io::RoleImage& color = frame.images.roles.at(Role::Color);
    afn::io::WriteOptions wo;
    wo.dataType = "float"; // features are read back exactly
    wo.inputs = inputs;
    wo.attributes["Software"] = softwareName();
    wo.attributes["Exif:ImageHistory"]
        = softwareName() + ": " + frame.ref.path + " " + describe() + " " + path;
    wo.attributes["afn:method"] = m_method;
    afn::io::writeImageAtomic(path, color.width, color.height, channels, m_output.data(), wo);
}

} // namespace afntool
