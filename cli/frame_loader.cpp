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
                refs.push_back({ afn::io::bmfrFramePath(input, f), f });
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
                refs.push_back({ paths[i], frames[i] });
        } else {
            if (!fs::exists(input, ec))
                throw CliError("no such file", input);
            refs.push_back({ input, -1 });
        }
    }
    return refs;
}

std::string outputPath(const std::string& pattern, const FrameRef& ref, std::size_t frameCount,
    const std::string& flag)
{
    if (afn::io::hasFramePattern(pattern)) {
        if (ref.frame < 0)
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

static bool isPseudoPath(const std::string& p)
{
    return p.find("#bmfr:") != std::string::npos;
}

LoadedFrame loadFrame(RunContext& ctx, const FrameRef& ref, bool keepAll)
{
    const Options& opts = ctx.options();
    LoadedFrame lf;
    lf.ref = ref;
    afn::io::ReadOptions ro;
    ro.overrides = opts.overrides;
    ro.keepAll = keepAll;
    ro.required = { afn::io::Role::Color };
    std::string fileSpace;
    try {
        lf.images = afn::io::readFrame(ref.path, ro);
        if (!isPseudoPath(ref.path)) {
            const afn::io::FileInfo info = afn::io::inspect(ref.path);
            auto it = info.attributes.find("oiio:ColorSpace");
            if (it != info.attributes.end())
                fileSpace = it->second;
            const afn::io::RoleChannels* c = lf.images.mapping.find(afn::io::Role::Color);
            if (c && c->subimage < static_cast<int>(info.subimages.size())) {
                const afn::io::SubimageInfo& si = info.subimages[c->subimage];
                lf.compression = si.compression;
                if (!c->indices.empty() && c->indices[0] < static_cast<int>(si.types.size()))
                    lf.beautyType = si.types[c->indices[0]];
            }
        }
    } catch (const afn::io::IoError& e) {
        throw CliError(e.what(), e.file().empty() ? ref.path : e.file());
    }
    if (lf.beautyType != "half")
        lf.beautyType = "float";

    afn::color::ColorManager& cm = ctx.color();
    const std::string working = cm.workingSpace();
    if (!opts.inColorSpace.empty()) {
        if (!cm.hasColorSpace(opts.inColorSpace))
            throw CliError(
                "--incolorspace '" + opts.inColorSpace + "' is not in the colour config");
        lf.colorSpace = opts.inColorSpace;
    } else if (!fileSpace.empty() && cm.hasColorSpace(fileSpace)) {
        lf.colorSpace = fileSpace;
    } else {
        if (!fileSpace.empty())
            warn("input colour space '" + fileSpace
                    + "' is unknown to the colour config; "
                      "treating the beauty as "
                    + working + " (" + ref.path + ")",
                opts.quiet);
        lf.colorSpace = working;
    }

    afn::io::RoleImage& color = lf.images.roles.at(afn::io::Role::Color);
    try {
        cm.toWorking(
            color.pixels.data(), color.width, color.height, color.components, lf.colorSpace);
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
