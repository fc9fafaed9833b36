// SPDX-License-Identifier: Apache-2.0
// Colour-space records in file headers. OpenImageIO 2.4 does not store oiio:ColorSpace in an
// OpenEXR file, so outputs are tagged the way current tools read them: the Color Interop Forum's
// `colorInteropID` (read by OpenImageIO 3 and OCIO 2.4+ configs) and OpenEXR's standard
// `chromaticities`. OCIO 2.1 configs carry no interop ids, so a space is matched by its name and
// aliases against the common names of each id below (the ACES and Blender configs' spellings).
#include "afn/color.hpp"

#include <algorithm>
#include <cctype>

namespace afn::color {
namespace {

// CIE xy of red, green, blue, white.
// clang-format off
const std::vector<float> kRec709 = { 0.64f, 0.33f, 0.30f, 0.60f, 0.15f, 0.06f, 0.3127f, 0.3290f };
const std::vector<float> kAp1 = { 0.713f, 0.293f, 0.165f, 0.830f, 0.128f, 0.044f, 0.32168f, 0.33767f };
const std::vector<float> kAp0 = { 0.7347f, 0.2653f, 0.0f, 1.0f, 0.0001f, -0.0770f, 0.32168f, 0.33767f };
const std::vector<float> kRec2020 = { 0.708f, 0.292f, 0.170f, 0.797f, 0.131f, 0.046f, 0.3127f, 0.3290f };
const std::vector<float> kP3D65 = { 0.680f, 0.320f, 0.265f, 0.690f, 0.150f, 0.060f, 0.3127f, 0.3290f };
// clang-format on

struct KnownSpace {
    const char* id;
    const std::vector<float>* chromaticities; ///< nullptr for data
    std::vector<std::string> names; ///< lower case
};

const std::vector<KnownSpace>& knownSpaces()
{
    static const std::vector<KnownSpace> kSpaces = {
        { "lin_ap1_scene", &kAp1, { "acescg", "lin_ap1", "aces - acescg" } },
        { "lin_ap0_scene", &kAp0, { "aces2065-1", "lin_ap0", "aces", "aces - aces2065-1" } },
        { "lin_rec709_scene", &kRec709,
            { "linear rec.709", "lin_rec709", "linear", "lin_srgb", "linear rec.709 (srgb)",
                "linear rec709", "utility - linear - srgb" } },
        { "lin_rec2020_scene", &kRec2020,
            { "linear rec.2020", "lin_rec2020", "utility - linear - rec.2020" } },
        { "lin_p3d65_scene", &kP3D65, { "linear p3-d65", "lin_p3d65" } },
        { "srgb_rec709_scene", &kRec709,
            { "srgb texture", "srgb_tx", "srgb_texture", "srgb - texture",
                "srgb encoded rec.709 (srgb)", "utility - srgb - texture" } },
        { "srgb_rec709_display", &kRec709, { "srgb", "srgb - display", "srgb display" } },
        { "data", nullptr, { "raw", "non-color", "non_color", "utility - raw", "data" } },
    };
    return kSpaces;
}

std::string lower(std::string s)
{
    std::transform(s.begin(), s.end(), s.begin(),
        [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return s;
}

} // namespace

ColorManager::FileTag ColorManager::fileTag(const std::string& space) const
{
    FileTag tag;
    const std::string name = canonicalName(space);
    if (name.empty())
        return tag;
    std::vector<std::string> names = aliases(name);
    names.push_back(name);
    for (std::string& n : names)
        n = lower(n);
    for (const KnownSpace& k : knownSpaces())
        for (const std::string& n : names)
            if (n == k.id || std::find(k.names.begin(), k.names.end(), n) != k.names.end()) {
                tag.interopId = k.id;
                if (k.chromaticities)
                    tag.chromaticities = *k.chromaticities;
                return tag;
            }
    return tag;
}

std::string ColorManager::spaceFromInteropId(const std::string& id) const
{
    if (id.empty())
        return {};
    // A config may name the space by the id itself, or by the id without its _scene suffix
    // (lin_ap1, lin_rec709: the aliases of ACES and afn's configs).
    std::vector<std::string> candidates = { id };
    for (const char* suffix : { "_scene", "_display" }) {
        const std::string s = suffix;
        if (id.size() > s.size() && id.compare(id.size() - s.size(), s.size(), s) == 0)
            candidates.push_back(id.substr(0, id.size() - s.size()));
    }
    for (const KnownSpace& k : knownSpaces())
        if (id == k.id)
            candidates.insert(candidates.end(), k.names.begin(), k.names.end());
    for (const std::string& c : candidates)
        if (hasColorSpace(c) && fileTag(c).interopId == id)
            return canonicalName(c);
    for (const std::string& c : candidates)
        if (hasColorSpace(c))
            return canonicalName(c);
    return {};
}

std::string ColorManager::integerFileSpace(int bits) const
{
    for (const char* name :
        { bits <= 8 ? "matte_paint" : "texture_paint", "sRGB", "color_picking" })
        if (hasColorSpace(name))
            return canonicalName(name);
    return workingSpace();
}

} // namespace afn::color
