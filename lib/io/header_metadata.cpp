// SPDX-License-Identifier: Apache-2.0
// The header of the part a frame's colour comes from, as an output should carry it over: windows,
// stored type, compression and typed attributes (as oiiotool and Nuke's Write keep them).
#include "oiio_util.h"

#include <set>

namespace afn::io::detail {
namespace {

/// True for attributes that describe the file rather than the picture, or that the writer sets
/// for each output itself.
bool isStructural(const std::string& name)
{
    static const std::set<std::string> kSkip
        = { "compression", "name", "type", "view", "chunkCount", "version", "tiles", "DateTime",
              "Software", "colorInteropID", "chromaticities", "planarconfig", "Orientation" };
    if (kSkip.count(name))
        return true;
    // Format-specific keys ("oiio:", "openexr:", "png:", "tiff:", "jpeg:", ...) are file
    // structure of the input's format; the history is continued by the writer's caller.
    static const char* const kPrefixes[] = { "oiio:", "openexr:", "png:", "tiff:", "jpeg:", "exr:",
        "targa:", "bmp:", "dpx:", "hdr:", "pnm:", "webp:", "ICCProfile" };
    for (const char* p : kPrefixes)
        if (name.rfind(p, 0) == 0)
            return true;
    return false;
}

} // namespace

FrameHeader readHeader(const OIIO::ImageSpec& spec, const std::string& format, int colorChannel)
{
    FrameHeader h;
    h.format = format;
    h.dataWindow = { spec.x, spec.y, spec.width, spec.height };
    h.displayWindow = { spec.full_x, spec.full_y, spec.full_width, spec.full_height };
    h.colorType = typeName(spec.channelformat(std::max(0, colorChannel)).basetype);
    if (format == "openexr")
        h.compression = spec.get_string_attribute("compression");
    h.colorSpace = spec.get_string_attribute("oiio:ColorSpace");
    h.colorInteropId = spec.get_string_attribute("colorInteropID");
    for (const OIIO::ParamValue& p : spec.extra_attribs) {
        const std::string name = p.name().string();
        const OIIO::TypeDesc type = p.type();
        if (isStructural(name) || type.basetype == OIIO::TypeDesc::PTR)
            continue;
        Attribute a;
        a.name = name;
        a.type = type.c_str();
        if (type == OIIO::TypeDesc::STRING) {
            a.text = p.get_string();
        } else if (type.basetype == OIIO::TypeDesc::STRING || p.nvalues() != 1
            || OIIO::TypeDesc(a.type.c_str()) != type) {
            continue; // string arrays, or a type whose name does not parse back (rational2i)
        } else {
            const auto* bytes = static_cast<const unsigned char*>(p.data());
            a.data.assign(bytes, bytes + type.size());
        }
        h.attributes.push_back(std::move(a));
    }
    return h;
}

void applyMetadata(OIIO::ImageSpec& spec, const std::vector<Attribute>& attributes)
{
    for (const Attribute& a : attributes) {
        const OIIO::TypeDesc type(a.type.c_str());
        if (type == OIIO::TypeDesc::STRING) {
            spec.attribute(a.name, a.text);
        } else if (type.basetype != OIIO::TypeDesc::UNKNOWN && a.data.size() == type.size()) {
            spec.attribute(a.name, type, a.data.data());
        }
    }
}

} // namespace afn::io::detail
