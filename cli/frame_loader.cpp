// SPDX-License-Identifier: Apache-2.0
#include "frame_loader.h"

#include "cli_error.h"
#include "progress.h"

#include <filesystem>

namespace afntool {

namespace fs = std::filesystem;

std::vector<FrameRef> resolveFrames(const Options& opts)
{
    if (opts.inputs.empty())
        throw CliError("no input given (see afntool --help)");
    std::vector<int> frames;
    if (!opts.frames.empty()) {
        try {
            frames = afn::io::parseFrameRange(opts.frames);
        } catch (const afn::io::IoError& e) {
            throw CliError(std::string("--frames: ") + e.what());
        }
    }
    std::vector<FrameRef> refs;
    for (const std::string& input : opts.inputs) {
        std::error_code ec;
        if (fs::is_directory(input, ec)) {
            if (!afn::io::isBmfrDataset(input))
                throw CliError("directory is not a BMFR-layout dataset (no color{N}.exr and "
                               "camera_matrices.h)",
                    input);
            if (frames.empty())
                throw CliError("a BMFR dataset folder needs --frames", input);
            for (int f : frames)
                refs.push_back({ afn::io::bmfrFramePath(input, f), f, true });
        } else if (afn::io::hasFramePattern(input)) {
            if (frames.empty())
                throw CliError("a frame pattern needs --frames A-B", input);
            std::vector<std::string> paths;
            try {
                paths = afn::io::expandSequence(input, frames, true);
            } catch (const afn::io::IoError& e) {
                throw CliError(e.what(), e.file());
            }
            for (std::size_t i = 0; i < paths.size(); ++i)
                refs.push_back({ paths[i], frames[i], true });
        } else {
            if (!fs::exists(input, ec))
                throw CliError("no such file", input);
            // Not silently ignored: the user meant a sequence (oiiotool errors the same way).
            if (!frames.empty())
                throw CliError("--frames " + opts.frames
                        + " needs a frame pattern in the input name (shot.####.exr, "
                          "shot.%04d.exr) or a dataset folder; this is a single file",
                    input);
            refs.push_back({ input, -1 });
        }
    }
    return refs;
}

std::string outputPath(const std::string& pattern, const FrameRef& ref, std::size_t frameCount,
    const std::string& flag)
{
    if (afn::io::hasFramePattern(pattern)) {
        if (!ref.numbered)
            throw CliError(flag + " has a frame pattern but the input is a single file", pattern);
        return afn::io::expandFramePattern(pattern, ref.frame);
    }
    if (frameCount > 1)
        throw CliError(flag + " needs a frame pattern (e.g. out.####.exr) for a sequence", pattern);
    return pattern;
}

afn::color::ColorManager& RunContext::color()
{
    if (!m_color) {
        try {
            m_color = std::make_unique<afn::color::ColorManager>(m_opts.colorConfig);
        } catch (const afn::color::ColorError& e) {
            throw CliError(std::string("colour config: ") + e.what(), m_opts.colorConfig);
        }
    }
    return *m_color;
}

namespace {

/// The colour space of the input beauty: --incolorspace; else the file's colorInteropID or
/// oiio:ColorSpace when the config knows it; else, for integer files without a tag, the space
/// the config gives such files (integerFileSpace: sRGB-encoded); else the working space.
std::string inputColorSpace(const afn::color::ColorManager& cm, const Options& opts,
    const afn::io::FrameHeader& header, const std::string& type, const std::string& path)
{
    if (!opts.inColorSpace.empty()) {
        if (!cm.hasColorSpace(opts.inColorSpace))
            throw CliError(
                "--incolorspace '" + opts.inColorSpace + "' is not in the colour config");
        return opts.inColorSpace;
    }
    if (const std::string s = cm.spaceFromInteropId(header.colorInteropId); !s.empty())
        return s;
    if (cm.hasColorSpace(header.colorSpace))
        return header.colorSpace;
    if (!header.colorSpace.empty())
        warn("input colour space '" + header.colorSpace
                + "' is unknown to the colour config; treating the beauty as " + cm.workingSpace()
                + " (" + path + ")",
            opts.quiet);
    else if (type == "uint8" || type == "uint16")
        return cm.integerFileSpace(type == "uint8" ? 8 : 16);
    return cm.workingSpace();
}

} // namespace

LoadedFrame loadFrame(RunContext& ctx, const FrameRef& ref, bool keepAll)
{
    const Options& opts = ctx.options();
    LoadedFrame lf;
    lf.ref = ref;
    afn::io::ReadOptions ro;
    ro.overrides = opts.overrides;
    // A --denoise:mask=CHANNEL reads a channel no role maps: every channel is read then.
    bool mask = false;
    for (const Action& a : opts.actions)
        mask = mask || (a.name == "denoise" && a.mods.count("mask"));
    ro.keepAll = keepAll || mask;
    // --denoise:passes= reads the light-path passes too.
    for (const Action& a : opts.actions)
        if (a.name == "denoise" && a.mods.count("passes") && a.mods.at("passes") != "none")
            ro.passes = true;
    ro.required = { afn::io::Role::Color };
    try {
        lf.images = afn::io::readFrame(ref.path, ro);
    } catch (const afn::io::IoError& e) {
        throw CliError(e.what(), e.file().empty() ? ref.path : e.file());
    }
    const afn::io::FrameHeader& header = lf.images.header;
    lf.beautyType = header.colorType;
    if (lf.beautyType != "half" && lf.beautyType != "uint8" && lf.beautyType != "uint16")
        lf.beautyType = "float";
    afn::color::ColorManager& cm = ctx.color();
    lf.colorSpace = inputColorSpace(cm, opts, header, lf.beautyType, ref.path);

    afn::io::RoleImage& color = lf.images.roles.at(afn::io::Role::Color);
    try {
        cm.toWorking(
            color.pixels.data(), color.width, color.height, color.components, lf.colorSpace);
        // Light passes and their colour factors are in the beauty's space, as the albedo.
        for (auto& [name, pass] : lf.images.passes)
            cm.toWorking(
                pass.pixels.data(), pass.width, pass.height, pass.components, lf.colorSpace);
        auto alb = lf.images.roles.find(afn::io::Role::Albedo);
        if (alb != lf.images.roles.end())
            cm.toWorking(alb->second.pixels.data(), alb->second.width, alb->second.height,
                alb->second.components, lf.colorSpace);
    } catch (const afn::color::ColorError& e) {
        throw CliError(std::string("colour conversion: ") + e.what(), ref.path);
    }
    lf.beauty.resize(static_cast<std::size_t>(color.width) * color.height * 3);
    for (std::size_t i = 0, n = static_cast<std::size_t>(color.width) * color.height; i < n; ++i)
        for (int c = 0; c < 3; ++c)
            lf.beauty[i * 3 + c] = color.pixels[i * color.components + c];
    return lf;
}

} // namespace afntool
