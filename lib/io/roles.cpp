// SPDX-License-Identifier: Apache-2.0
// Role names, component counts, space-tag parsing and the "--aov" override parser.
#include "io_internal.h"

#include <array>
#include <filesystem>

namespace afn::io {
namespace {

constexpr std::array<const char*, kNumRoles> kRoleNames = { "color", "albedo", "normal", "depth",
    "position", "motion", "alpha", "variance", "specular" };
static_assert(kRoleNames.size() == kNumRoles, "one name per role");

std::string trim(const std::string& s)
{
    const auto b = s.find_first_not_of(" \t");
    if (b == std::string::npos)
        return {};
    const auto e = s.find_last_not_of(" \t");
    return s.substr(b, e - b + 1);
}

bool parseBool(const std::string& v, bool& out)
{
    if (v == "1" || v == "true" || v == "yes" || v == "on")
        return out = true, true;
    if (v == "0" || v == "false" || v == "no" || v == "off")
        return out = false, true;
    return false;
}

} // namespace

const char* roleName(Role role)
{
    const int i = static_cast<int>(role);
    return i >= 0 && i < kNumRoles ? kRoleNames[i] : "unknown";
}

std::optional<Role> roleFromName(const std::string& name)
{
    for (int i = 0; i < kNumRoles; ++i)
        if (name == kRoleNames[i])
            return static_cast<Role>(i);
    if (name == "colour" || name == "beauty")
        return Role::Color;
    return std::nullopt;
}

int roleComponents(Role role)
{
    switch (role) {
    case Role::Depth:
    case Role::Alpha:
        return 1;
    case Role::Motion:
        return 2;
    default:
        return 3;
    }
}

const RoleChannels* RoleMapping::find(Role role) const
{
    for (const RoleChannels& r : roles)
        if (r.role == role)
            return &r;
    return nullptr;
}

void parseOverride(const std::string& text, MappingOverrides& overrides)
{
    static const std::string kNone = "none";
    const auto eq = text.find('=');
    if (eq == std::string::npos || eq == 0 || eq + 1 == text.size())
        throw IoError("--aov expects role=channels or tag=value, got '" + text + "'");
    const std::string key = trim(text.substr(0, eq));
    const std::string value = trim(text.substr(eq + 1));
    if (key.find('.') != std::string::npos) {
        SpaceTag probe;
        if (!detail::applyTag(probe, key, value))
            throw IoError("--aov: unknown tag or value '" + text
                + "' (normal.space=world|camera|camera-toward-viewer, "
                  "depth.kind=planar|radial, motion.direction=to-previous|to-next, "
                  "motion.yUp=true|false, motion.units=pixels|ndc|uv, "
                  "color.demodulated=true|false)");
        overrides.tags[key] = value;
        return;
    }
    if (key == "lights") {
        // Light-path passes: "lights=none" or "lights=A,B*F,..." (B times the factor layer F).
        std::vector<std::string> lights;
        if (value != kNone) {
            std::size_t start = 0;
            while (start <= value.size()) {
                const auto comma = value.find(',', start);
                const std::string part = trim(value.substr(
                    start, comma == std::string::npos ? std::string::npos : comma - start));
                const auto star = part.find('*');
                if (part.empty() || star == 0
                    || (star != std::string::npos
                        && (star + 1 == part.size()
                            || part.find('*', star + 1) != std::string::npos)))
                    throw IoError("--aov lights: expected LAYER or LAYER*FACTOR in '" + text + "'");
                lights.push_back(part);
                if (comma == std::string::npos)
                    break;
                start = comma + 1;
            }
        }
        overrides.lights = lights;
        return;
    }
    const std::optional<Role> role = roleFromName(key);
    if (!role)
        throw IoError("--aov: unknown role '" + key + "' in '" + text + "'");
    std::vector<std::string> names;
    std::size_t start = 0;
    while (start <= value.size()) {
        const auto comma = value.find(',', start);
        const std::string part = trim(
            value.substr(start, comma == std::string::npos ? std::string::npos : comma - start));
        if (part.empty())
            throw IoError("--aov: empty channel name in '" + text + "'");
        names.push_back(part);
        if (comma == std::string::npos)
            break;
        start = comma + 1;
    }
    // One name is a layer prefix (or a single channel); otherwise one name per component. A
    // variance may be one channel or three.
    const int n = static_cast<int>(names.size());
    const bool ok = n == 1 || n == roleComponents(*role) || (*role == Role::Variance && n == 3);
    if (!ok)
        throw IoError("--aov: role '" + key + "' takes 1 layer name or "
            + std::to_string(roleComponents(*role)) + " channel names, got " + std::to_string(n)
            + " in '" + text + "'");
    overrides.channels[*role] = names;
}

std::vector<std::pair<std::string, std::string>> SpaceTag::parameters() const
{
    return { { AFN_CONVENTION_NORMAL_SPACE, normalSpace }, { AFN_CONVENTION_DEPTH_KIND, depthKind },
        { AFN_CONVENTION_MOTION_DIRECTION, motionDirection },
        { AFN_CONVENTION_MOTION_Y_UP, motionYUp ? "true" : "false" },
        { AFN_CONVENTION_MOTION_UNITS, motionUnits },
        { AFN_CONVENTION_COLOR_DEMODULATED, colorDemodulated ? "true" : "false" } };
}

namespace detail {

bool applyTag(SpaceTag& tag, const std::string& key, const std::string& value)
{
    if (key == AFN_CONVENTION_NORMAL_SPACE) {
        if (value != "world" && value != "camera" && value != "camera-toward-viewer")
            return false;
        tag.normalSpace = value;
    } else if (key == AFN_CONVENTION_DEPTH_KIND) {
        if (value != "planar" && value != "radial")
            return false;
        tag.depthKind = value;
    } else if (key == AFN_CONVENTION_MOTION_DIRECTION) {
        if (value != "to-previous" && value != "to-next")
            return false;
        tag.motionDirection = value;
    } else if (key == AFN_CONVENTION_MOTION_Y_UP) {
        return parseBool(value, tag.motionYUp);
    } else if (key == AFN_CONVENTION_MOTION_UNITS) {
        if (value != "pixels" && value != "ndc" && value != "uv")
            return false;
        tag.motionUnits = value;
    } else if (key == AFN_CONVENTION_COLOR_DEMODULATED) {
        return parseBool(value, tag.colorDemodulated);
    } else {
        return false;
    }
    return true;
}

std::pair<std::string, std::string> splitLast(const std::string& name)
{
    const auto dot = name.rfind('.');
    if (dot == std::string::npos)
        return { std::string(), name };
    return { name.substr(0, dot), name.substr(dot + 1) };
}

void requireFile(const std::string& path)
{
    std::error_code ec;
    const auto st = std::filesystem::status(path, ec);
    if (ec || !std::filesystem::exists(st))
        throw IoError("file not found", path);
    if (std::filesystem::is_directory(st))
        throw IoError("is a directory, not an image", path);
}

} // namespace detail
} // namespace afn::io
