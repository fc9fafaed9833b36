// SPDX-License-Identifier: Apache-2.0
// The BMFR dataset layout: <scene>[/inputs]/{color,albedo,shading_normal,world_position,
// reference}{N}.exr (no zero padding) and camera_matrices.h with named C arrays.
#include "oiio_util.h"

#include <cctype>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace afn::io {
namespace {

namespace fs = std::filesystem;

bool hasColorFrame(const fs::path& dir)
{
    std::error_code ec;
    if (!fs::is_regular_file(dir / "camera_matrices.h", ec))
        return false;
    for (const auto& e : fs::directory_iterator(dir, ec)) {
        const std::string n = e.path().filename().string();
        if (n.size() > 9 && n.rfind("color", 0) == 0 && n.compare(n.size() - 4, 4, ".exr") == 0
            && std::isdigit(static_cast<unsigned char>(n[5])))
            return true;
    }
    return false;
}

/// The folder holding the files: dir itself or dir/inputs.
fs::path bmfrBase(const std::string& dir)
{
    if (hasColorFrame(dir))
        return dir;
    if (hasColorFrame(fs::path(dir) / "inputs"))
        return fs::path(dir) / "inputs";
    throw IoError("not a BMFR scene folder (no color{N}.exr and camera_matrices.h in it or in "
                  "inputs/)",
        dir);
}

/// The file's R,G,B by name.
RoleImage readRgb(const std::string& path)
{
    auto in = detail::openInput(path);
    const OIIO::ImageSpec spec = in->spec(0, 0);
    std::vector<int> idx;
    for (const char* c : { "R", "G", "B" }) {
        const int i = spec.channelindex(c);
        if (i < 0)
            throw IoError(std::string("no channel ") + c + " (BMFR files hold R,G,B)", path);
        idx.push_back(i);
    }
    std::vector<float> all(static_cast<std::size_t>(spec.width) * spec.height * spec.nchannels);
    if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, all.data()))
        throw IoError(
            "cannot read pixels (truncated or corrupt file?): " + detail::inputError(in.get()),
            path);
    RoleImage img { spec.width, spec.height, 3, {} };
    const std::size_t n = static_cast<std::size_t>(spec.width) * spec.height;
    img.pixels.resize(n * 3);
    for (std::size_t p = 0; p < n; ++p)
        for (int c = 0; c < 3; ++c)
            img.pixels[p * 3 + c] = all[p * spec.nchannels + idx[c]];
    return img;
}

/// The header text with comments removed.
std::string stripComments(const std::string& s)
{
    std::string out;
    for (std::size_t i = 0; i < s.size(); ++i) {
        if (s.compare(i, 2, "//") == 0) {
            i = s.find('\n', i);
            if (i == std::string::npos)
                break;
            out += '\n';
        } else if (s.compare(i, 2, "/*") == 0) {
            i = s.find("*/", i + 2);
            if (i == std::string::npos)
                break;
            ++i;
            out += ' ';
        } else {
            out += s[i];
        }
    }
    return out;
}

bool isIdent(char c)
{
    return std::isalnum(static_cast<unsigned char>(c)) || c == '_';
}

/// Numbers of the initialiser of the declaration named `name` (an array or a scalar); nullopt
/// when the header does not declare it.
std::optional<std::vector<float>> initializer(
    const std::string& text, const std::string& name, const std::string& file)
{
    std::size_t at = 0;
    while ((at = text.find(name, at)) != std::string::npos) {
        const bool whole = (at == 0 || !isIdent(text[at - 1]))
            && (at + name.size() >= text.size() || !isIdent(text[at + name.size()]));
        if (whole)
            break;
        at += name.size();
    }
    if (at == std::string::npos)
        return std::nullopt;
    const std::size_t eq = text.find('=', at), semi = text.find(';', at);
    if (eq == std::string::npos || semi == std::string::npos || semi < eq)
        throw IoError("cannot parse the initialiser of '" + name + "'", file);
    std::vector<float> values;
    const char* p = text.c_str() + eq + 1;
    const char* end = text.c_str() + semi;
    while (p < end) {
        if (std::isdigit(static_cast<unsigned char>(*p)) || *p == '-' || *p == '+' || *p == '.') {
            char* next = nullptr;
            const float v = std::strtof(p, &next);
            if (next == p)
                throw IoError("bad number in '" + name + "'", file);
            values.push_back(v);
            p = next;
            if (p < end && (*p == 'f' || *p == 'F'))
                ++p;
        } else if (*p == '{' || *p == '}' || *p == ','
            || std::isspace(static_cast<unsigned char>(*p))) {
            ++p;
        } else {
            throw IoError("unexpected '" + std::string(1, *p) + "' in '" + name + "'", file);
        }
    }
    return values;
}

} // namespace

bool isBmfrDataset(const std::string& dir)
{
    return hasColorFrame(dir) || hasColorFrame(fs::path(dir) / "inputs");
}

std::string bmfrFramePath(const std::string& dir, int frame)
{
    return dir + "#bmfr:" + std::to_string(frame);
}

std::vector<FrameCamera> parseCameraMatrices(const std::string& headerPath)
{
    detail::requireFile(headerPath);
    std::ifstream f(headerPath);
    std::stringstream ss;
    ss << f.rdbuf();
    if (!f)
        throw IoError("cannot read camera header", headerPath);
    const std::string text = stripComments(ss.str());
    const auto mats = initializer(text, "camera_matrices", headerPath);
    if (!mats || mats->empty() || mats->size() % 16 != 0)
        throw IoError("camera_matrices must be a [frames][4][4] float array", headerPath);
    const auto offsets = initializer(text, "pixel_offsets", headerPath);
    const auto posLimit = initializer(text, "position_limit_squared", headerPath);
    const auto nrmLimit = initializer(text, "normal_limit_squared", headerPath);
    std::vector<FrameCamera> cams(mats->size() / 16);
    for (std::size_t k = 0; k < cams.size(); ++k) {
        FrameCamera& c = cams[k];
        for (int i = 0; i < 16; ++i)
            c.viewProjection[i] = (*mats)[k * 16 + i];
        // Missing offsets fall back to the pixel centre (0.5, 0.5), as WSKPN assumes.
        const bool haveOff = offsets && offsets->size() >= 2 * (k + 1);
        c.pixelOffset[0] = haveOff ? (*offsets)[2 * k] : 0.5f;
        c.pixelOffset[1] = haveOff ? (*offsets)[2 * k + 1] : 0.5f;
        c.positionLimitSquared = posLimit && posLimit->size() == 1 ? posLimit->front() : -1.0f;
        c.normalLimitSquared = nrmLimit && nrmLimit->size() == 1 ? nrmLimit->front() : -1.0f;
    }
    return cams;
}

namespace detail {

FrameImages readBmfrFrame(const std::string& dir, int frame, const ReadOptions& options)
{
    const fs::path base = bmfrBase(dir);
    const std::string n = std::to_string(frame);
    FrameImages out;
    out.path = bmfrFramePath(dir, frame);
    out.mapping.renderer = "bmfr";
    out.mapping.tag.normalSpace = "world";
    out.mapping.tag.colorDemodulated = true; // colour is incoming light; reference is modulated
    struct Buffer {
        Role role;
        const char* stem;
    };
    const Buffer buffers[] = { { Role::Color, "color" }, { Role::Albedo, "albedo" },
        { Role::Normal, "shading_normal" }, { Role::Position, "world_position" } };
    for (const Buffer& b : buffers) {
        const fs::path file = base / (std::string(b.stem) + n + ".exr");
        std::error_code ec;
        if (!fs::exists(file, ec)) {
            out.mapping.lookedFor[b.role] = { file.string() };
            continue;
        }
        out.roles[b.role] = readRgb(file.string());
        out.mapping.roles.push_back(
            { b.role, 0, { "R", "G", "B" }, { 0, 1, 2 }, "BMFR " + file.filename().string() });
    }
    for (Role r : options.required)
        if (!out.mapping.find(r))
            throw IoError(missingRoleMessage(r, out.mapping, ""), out.path);
    for (const auto& [key, value] : options.overrides.tags)
        if (!applyTag(out.mapping.tag, key, value))
            throw IoError("--aov: invalid tag " + key + "=" + value, out.path);
    const RoleImage* ref = out.roles.count(Role::Color) ? &out.roles.at(Role::Color) : nullptr;
    for (const auto& [role, img] : out.roles)
        if (ref && (img.width != ref->width || img.height != ref->height))
            throw IoError(std::string("BMFR ") + roleName(role) + " buffer size differs from color",
                out.path);
    if (ref) {
        out.header.dataWindow = out.header.displayWindow = { 0, 0, ref->width, ref->height };
        out.header.colorType = "float";
    }
    const fs::path refFile = base / ("reference" + n + ".exr");
    std::error_code ec;
    if (fs::exists(refFile, ec))
        out.reference = readRgb(refFile.string());

    const std::vector<FrameCamera> cams
        = parseCameraMatrices((base / "camera_matrices.h").string());
    if (frame < static_cast<int>(cams.size()))
        out.camera = cams[frame];
    else
        out.mapping.warnings.push_back("camera_matrices.h has no frame " + n);

    if (options.keepAll && ref) {
        LayeredImage all;
        all.width = ref->width;
        all.height = ref->height;
        all.dataWindow = all.displayWindow = { 0, 0, ref->width, ref->height };
        all.compression = "zip";
        std::vector<const RoleImage*> srcs;
        for (const RoleChannels& rc : out.mapping.roles) {
            for (const char* c : { ".R", ".G", ".B" }) {
                all.channels.push_back(std::string(roleName(rc.role)) + c);
                all.types.push_back("float");
            }
            srcs.push_back(&out.roles.at(rc.role));
        }
        const std::size_t np = static_cast<std::size_t>(all.width) * all.height,
                          nch = srcs.size() * 3;
        all.pixels.resize(np * nch);
        for (std::size_t p = 0; p < np; ++p)
            for (std::size_t s = 0; s < srcs.size(); ++s)
                for (int c = 0; c < 3; ++c)
                    all.pixels[p * nch + s * 3 + c] = srcs[s]->pixels[p * 3 + c];
        out.all = std::move(all);
    }
    return out;
}

} // namespace detail
} // namespace afn::io
