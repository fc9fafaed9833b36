// SPDX-License-Identifier: Apache-2.0
// readFrame: decode each needed subimage once (as float) and gather the mapped roles by index.
#include "oiio_util.h"

#include <set>

namespace afn::io {
namespace {

constexpr const char* kBmfrTag = "#bmfr:";

/// Channels [first, first + nch) of a subimage, interleaved, data window size.
struct Decoded {
    int width = 0, height = 0, first = 0, nch = 0;
    std::vector<float> pixels;
};

/// One read_image call per subimage over the range of channels needed: OpenEXR decompresses whole
/// scanline blocks, so one call per role would decode the same blocks again for each role.
/// The channels are read in the file's own types and converted to float here: OpenImageIO's
/// converting read stages every call through a 64 MB buffer, whatever the image size.
Decoded decode(OIIO::ImageInput& in, int sub, const OIIO::ImageSpec& spec, int first, int end,
    const std::string& path)
{
    Decoded d { spec.width, spec.height, first, end - first, {} };
    const std::size_t pixels = static_cast<std::size_t>(d.width) * d.height;
    d.pixels.resize(pixels * d.nch);
    const std::size_t nativePixel = spec.pixel_bytes(first, end, /*native=*/true);
    std::vector<unsigned char> native(pixels * nativePixel);
    bool ok = in.read_image(sub, 0, first, end, OIIO::TypeUnknown, native.data());
    const OIIO::stride_t dstPixel = static_cast<OIIO::stride_t>(d.nch * sizeof(float));
    std::size_t offset = 0;
    for (int c = 0; ok && c < d.nch; ++c) {
        const OIIO::TypeDesc type = spec.channelformat(first + c);
        ok = OIIO::convert_image(1, d.width, d.height, 1, native.data() + offset, type,
            static_cast<OIIO::stride_t>(nativePixel),
            static_cast<OIIO::stride_t>(nativePixel) * d.width, OIIO::AutoStride,
            d.pixels.data() + c, OIIO::TypeDesc::FLOAT, dstPixel, dstPixel * d.width,
            OIIO::AutoStride);
        offset += type.size();
    }
    if (!ok)
        throw IoError(
            "cannot read pixels (truncated or corrupt file?): " + detail::inputError(&in), path);
    return d;
}

RoleImage gather(const Decoded& d, const std::vector<int>& indices)
{
    RoleImage img;
    img.width = d.width;
    img.height = d.height;
    img.components = static_cast<int>(indices.size());
    const std::size_t n = static_cast<std::size_t>(d.width) * d.height;
    img.pixels.resize(n * indices.size());
    for (std::size_t i = 0; i < n; ++i)
        for (std::size_t c = 0; c < indices.size(); ++c)
            img.pixels[i * indices.size() + c] = d.pixels[i * d.nch + indices[c] - d.first];
    return img;
}

bool sameWindow(const OIIO::ImageSpec& a, const OIIO::ImageSpec& b)
{
    return a.x == b.x && a.y == b.y && a.width == b.width && a.height == b.height;
}

/// String attributes a writer should carry over (Frame, Camera, cycles.*, ...), not file
/// structure (compression, part names, OIIO bookkeeping).
std::map<std::string, std::string> keptAttributes(const OIIO::ImageSpec& spec)
{
    static const std::set<std::string> skip
        = { "compression", "name", "type", "view", "chunkCount", "version", "tiles" };
    std::map<std::string, std::string> out;
    for (const OIIO::ParamValue& p : spec.extra_attribs) {
        const std::string n = p.name().string();
        if (p.type() != OIIO::TypeDesc::STRING || skip.count(n) || n.rfind("oiio:", 0) == 0
            || n.rfind("openexr:", 0) == 0)
            continue;
        out[n] = p.get_string();
    }
    return out;
}

/// Every channel of the subimages sharing the reference data window. Channels of the first part
/// keep their names; later parts are prefixed "<part>." (unless already so named).
LayeredImage layered(const std::vector<OIIO::ImageSpec>& specs, const std::vector<Decoded>& dec,
    int ref, std::vector<std::string>& warnings)
{
    const OIIO::ImageSpec& rs = specs[ref];
    LayeredImage all;
    all.width = rs.width;
    all.height = rs.height;
    all.dataWindow = { rs.x, rs.y, rs.width, rs.height };
    all.displayWindow = { rs.full_x, rs.full_y, rs.full_width, rs.full_height };
    all.attributes = keptAttributes(specs.front());
    all.compression = specs.front().get_string_attribute("compression");
    std::vector<std::pair<int, int>> src; // (subimage, channel)
    std::set<std::string> used;
    for (int s = 0; s < static_cast<int>(specs.size()); ++s) {
        if (!sameWindow(specs[s], rs)) {
            warnings.push_back(
                "part " + std::to_string(s) + " has a different data window: not kept");
            continue;
        }
        std::string part = detail::partName(specs[s]);
        if (part.empty())
            part = "part" + std::to_string(s);
        for (int c = 0; c < specs[s].nchannels; ++c) {
            std::string name = specs[s].channelnames[c];
            if (s > 0 && (name.rfind(part + ".", 0) != 0 || used.count(name)))
                name = part + "." + name;
            if (!used.insert(name).second)
                continue;
            all.channels.push_back(name);
            all.types.push_back(detail::typeName(specs[s].channelformat(c).basetype));
            src.emplace_back(s, c);
        }
    }
    const std::size_t n = static_cast<std::size_t>(all.width) * all.height, nch = src.size();
    all.pixels.resize(n * nch);
    for (std::size_t k = 0; k < nch; ++k) {
        const Decoded& d = dec[src[k].first];
        for (std::size_t i = 0; i < n; ++i)
            all.pixels[i * nch + k] = d.pixels[i * d.nch + src[k].second - d.first];
    }
    return all;
}

bool allZero(const RoleImage& img)
{
    for (float v : img.pixels)
        if (v != 0.0f)
            return false;
    return true;
}

} // namespace

FrameImages readFrame(const std::string& path, const ReadOptions& options)
{
    if (const auto at = path.rfind(kBmfrTag); at != std::string::npos) {
        const std::string num = path.substr(at + std::string(kBmfrTag).size());
        int frame = -1;
        try {
            std::size_t used = 0;
            frame = std::stoi(num, &used);
            if (used != num.size())
                frame = -1;
        } catch (const std::exception&) {
        }
        if (frame < 0)
            throw IoError("bad BMFR frame path (expected <dir>#bmfr:N)", path);
        return detail::readBmfrFrame(path.substr(0, at), frame, options);
    }

    auto in = detail::openInput(path);
    const std::vector<OIIO::ImageSpec> specs = detail::readSpecs(*in, path);
    FrameImages out;
    out.path = path;
    const FileInfo info = detail::infoFromSpecs(path, in->format_name(), specs);
    out.mapping = mapRoles(info, options.overrides);
    for (Role r : options.required)
        if (!out.mapping.find(r))
            throw IoError(
                detail::missingRoleMessage(r, out.mapping, detail::channelSummary(info)), path);

    // All roles share the colour's data window (the first part's when there is no colour).
    const RoleChannels* color = out.mapping.find(Role::Color);
    out.samples
        = samplesPerPixel(info, color && !color->channels.empty() ? color->channels[0] : "");
    const int ref = color ? color->subimage : 0;
    out.header = detail::readHeader(
        specs[ref], in->format_name(), color && !color->indices.empty() ? color->indices[0] : 0);
    std::vector<RoleChannels> kept;
    for (const RoleChannels& rc : out.mapping.roles) {
        if (sameWindow(specs[rc.subimage], specs[ref])) {
            kept.push_back(rc);
            continue;
        }
        const std::string msg = std::string(roleName(rc.role)) + " (part "
            + std::to_string(rc.subimage) + ") has a different data window from the colour";
        for (Role r : options.required)
            if (r == rc.role)
                throw IoError(msg, path);
        out.mapping.warnings.push_back(msg + ": ignored");
    }
    out.mapping.roles = kept;
    out.passRecipe = findLightPasses(info, out.mapping, options.overrides);
    std::vector<LightPass> passesRead;
    if (options.passes) {
        for (const auto* list : { &out.passRecipe.lights, &out.passRecipe.factors })
            for (const LightPass& p : *list) {
                if (sameWindow(specs[p.subimage], specs[ref]))
                    passesRead.push_back(p);
                else
                    out.mapping.warnings.push_back("light pass " + p.name
                        + " has a different data window from the colour: not read");
            }
    }

    // Channel range to decode per subimage: the roles' channels, or all with keepAll.
    const int nsub = static_cast<int>(specs.size());
    std::vector<std::pair<int, int>> range(nsub, { 0, 0 });
    for (const RoleChannels& rc : kept)
        for (int i : rc.indices) {
            auto& [lo, hi] = range[rc.subimage];
            lo = hi == 0 ? i : std::min(lo, i);
            hi = std::max(hi, i + 1);
        }
    for (const LightPass& p : passesRead)
        for (int i : p.indices) {
            auto& [lo, hi] = range[p.subimage];
            lo = hi == 0 ? i : std::min(lo, i);
            hi = std::max(hi, i + 1);
        }
    if (options.keepAll)
        for (int s = 0; s < nsub; ++s)
            if (sameWindow(specs[s], specs[ref]))
                range[s] = { 0, specs[s].nchannels };
    std::vector<Decoded> dec(nsub);
    for (int s = 0; s < nsub; ++s)
        if (range[s].second > range[s].first)
            dec[s] = decode(*in, s, specs[s], range[s].first, range[s].second, path);
    for (const RoleChannels& rc : kept)
        out.roles[rc.role] = gather(dec[rc.subimage], rc.indices);
    for (const LightPass& p : passesRead)
        out.passes[p.name] = gather(dec[p.subimage], p.indices);

    auto motion = out.roles.find(Role::Motion);
    if (motion != out.roles.end() && out.mapping.renderer == "blender" && allZero(motion->second))
        out.mapping.warnings.push_back(
            "Vector pass is all zero: motion blur was on when rendering, so it holds no motion");

    if (options.keepAll)
        out.all = layered(specs, dec, ref, out.mapping.warnings);
    return out;
}

} // namespace afn::io
