// SPDX-License-Identifier: Apache-2.0
// Header inspection: subimages, channels with their types, windows, compression, attributes.
#include "oiio_util.h"

#include <cstdlib>

namespace afn::io {
namespace detail {

std::string inputError(OIIO::ImageInput* in)
{
    std::string msg = in ? in->geterror() : std::string();
    if (msg.empty())
        msg = OIIO::geterror();
    if (msg.empty())
        msg = "unknown OpenImageIO error";
    return msg;
}

std::unique_ptr<OIIO::ImageInput> openInput(const std::string& path)
{
    requireFile(path);
    checkExrHeader(path);
    auto in = OIIO::ImageInput::open(path);
    if (!in)
        throw IoError("cannot read image: " + inputError(nullptr), path);
    return in;
}

std::vector<OIIO::ImageSpec> readSpecs(OIIO::ImageInput& in, const std::string& path)
{
    std::vector<OIIO::ImageSpec> specs;
    for (int s = 0; s < 10000; ++s) {
        if (s > 0 && !in.seek_subimage(s, 0))
            break;
        specs.push_back(in.spec(s, 0));
    }
    in.geterror(); // seeking past the last subimage records an error: drop it
    if (specs.empty() || specs.front().nchannels <= 0)
        throw IoError("image has no channels", path);
    // Deep images hold a variable number of samples per pixel; reading them as flat pixels fails
    // deep inside OpenImageIO with a message about a truncated or corrupt file.
    for (const OIIO::ImageSpec& spec : specs)
        if (spec.deep)
            throw IoError("deep EXR is not supported: afn reads flat images (flatten it first, "
                          "e.g. oiiotool in.exr --flatten -o flat.exr)",
                path);
    return specs;
}

std::string partName(const OIIO::ImageSpec& spec)
{
    std::string name = spec.get_string_attribute("oiio:subimagename");
    if (name.empty())
        name = spec.get_string_attribute("name");
    return name;
}

std::string typeName(int basetype)
{
    return OIIO::TypeDesc(static_cast<OIIO::TypeDesc::BASETYPE>(basetype)).c_str();
}

FileInfo infoFromSpecs(
    const std::string& path, const std::string& format, const std::vector<OIIO::ImageSpec>& specs)
{
    FileInfo info;
    info.path = path;
    info.format = format;
    for (const OIIO::ImageSpec& spec : specs) {
        SubimageInfo si;
        if (specs.size() > 1)
            si.name = detail::partName(spec);
        si.dataWindow = { spec.x, spec.y, spec.width, spec.height };
        si.displayWindow = { spec.full_x, spec.full_y, spec.full_width, spec.full_height };
        si.channels = spec.channelnames;
        for (int c = 0; c < spec.nchannels; ++c)
            si.types.push_back(detail::typeName(spec.channelformat(c).basetype));
        si.compression = spec.get_string_attribute("compression");
        info.subimages.push_back(std::move(si));
    }
    for (const OIIO::ParamValue& p : specs.front().extra_attribs)
        info.attributes[p.name().string()] = p.get_string();
    return info;
}

} // namespace detail

FileInfo inspect(const std::string& path)
{
    auto in = detail::openInput(path);
    return detail::infoFromSpecs(path, in->format_name(), detail::readSpecs(*in, path));
}

std::optional<int> samplesPerPixel(const FileInfo& info, const std::string& colorChannel)
{
    const std::string head = "cycles.", tail = ".samples";
    std::vector<std::pair<std::string, std::string>> found; // (layer, value)
    for (const auto& [name, value] : info.attributes)
        if (name.size() > head.size() + tail.size() && name.compare(0, head.size(), head) == 0
            && name.compare(name.size() - tail.size(), tail.size(), tail) == 0)
            found.emplace_back(
                name.substr(head.size(), name.size() - head.size() - tail.size()), value);
    const std::pair<std::string, std::string>* pick = found.size() == 1 ? &found.front() : nullptr;
    for (const auto& f : found)
        if (colorChannel.compare(0, f.first.size() + 1, f.first + ".") == 0)
            pick = &f;
    if (!pick)
        return std::nullopt;
    char* end = nullptr;
    const long n = std::strtol(pick->second.c_str(), &end, 10);
    if (end == pick->second.c_str() || *end != '\0' || n < 1 || n > (1L << 30))
        return std::nullopt;
    return static_cast<int>(n);
}

} // namespace afn::io
