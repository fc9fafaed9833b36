// SPDX-License-Identifier: Apache-2.0
#include "output_header.h"

#include "cli_error.h"

#include "afn/afn.h"

#include <cstring>

namespace afntool {

namespace {

constexpr const char* kHistory = "Exif:ImageHistory"; // oiiotool's --history attribute

} // namespace

std::string softwareName()
{
    return "afntool " + std::to_string(AFN_VERSION_MAJOR) + "." + std::to_string(AFN_VERSION_MINOR)
        + "." + std::to_string(AFN_VERSION_PATCH);
}

bool isIntegerType(const std::string& type)
{
    return type == "uint8" || type == "uint16";
}

std::string outputDataType(
    const Options& opts, const LoadedFrame& frame, const afn::io::OutputFormat& format)
{
    return format.storedType(opts.dataType.empty() ? frame.beautyType : opts.dataType);
}

std::string outputColorSpace(RunContext& ctx, const LoadedFrame& frame, const std::string& type)
{
    const Options& opts = ctx.options();
    afn::color::ColorManager& cm = ctx.color();
    if (!opts.outColorSpace.empty()) {
        if (!cm.hasColorSpace(opts.outColorSpace))
            throw CliError("--outcolorspace '" + opts.outColorSpace
                + "' is not in the colour config (" + cm.config().path + ")");
        return cm.canonicalName(opts.outColorSpace);
    }
    const bool integerIn = isIntegerType(frame.beautyType);
    if (isIntegerType(type))
        return integerIn ? frame.colorSpace : cm.integerFileSpace(type == "uint8" ? 8 : 16);
    return integerIn ? cm.workingSpace() : frame.colorSpace;
}

void describeOutput(RunContext& ctx, const LoadedFrame& frame, const std::string& action,
    const std::string& colorSpace, const afn::io::OutputFormat& format, afn::io::WriteOptions& wo)
{
    const afn::io::FrameHeader& header = frame.images.header;
    wo.metadata = header.attributes;
    if (header.dataWindow.width > 0 && header.displayWindow.width > 0) {
        wo.dataWindow = header.dataWindow;
        wo.displayWindow = header.displayWindow;
    }
    wo.attributes["Software"] = softwareName();

    // One history line per output, appended to the input's (as oiiotool --history does).
    std::string line = softwareName() + ": " + frame.ref.path;
    for (const std::string& step : frame.history)
        line += " " + step;
    line += " " + action;
    std::string history;
    for (const afn::io::Attribute& a : header.attributes)
        if (a.name == kHistory && a.type == "string" && !a.text.empty())
            history = a.text + "\n";
    wo.attributes[kHistory] = history + line;

    if (colorSpace.empty())
        return;
    wo.attributes["oiio:ColorSpace"] = colorSpace;
    if (format.name != "openexr")
        return;
    const afn::color::ColorManager::FileTag tag = ctx.color().fileTag(colorSpace);
    if (!tag.interopId.empty())
        wo.attributes["colorInteropID"] = tag.interopId;
    if (tag.chromaticities.size() == 8) {
        afn::io::Attribute chroma { "chromaticities", "float[8]", {}, {} };
        chroma.data.resize(8 * sizeof(float));
        std::memcpy(chroma.data.data(), tag.chromaticities.data(), chroma.data.size());
        wo.metadata.push_back(std::move(chroma));
    }
}

} // namespace afntool
