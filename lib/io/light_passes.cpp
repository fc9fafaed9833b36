// SPDX-License-Identifier: Apache-2.0
// The light-path passes a compositor rebuilds the beauty from, by renderer (facts: the project's
// reference notes, ../shared/reference/history-and-passes.md):
//   Blender Cycles  Combined = (DiffDir + DiffInd) x DiffCol + (GlossDir + GlossInd) x GlossCol
//                             + (TransDir + TransInd) x TransCol + Emit + Env [+ VolumeDir
//                             + VolumeInd]; light groups Combined_<group> add up to Combined.
//   Arnold          beauty = diffuse + specular + transmission + sss + coat + sheen + volume
//                             + emission + background, each family as <f>_direct + <f>_indirect
//                             where both are written, else <f>; or direct + indirect + emission
//                             + background (its built-in LPEs); light groups RGBA_<group>.
//   V-Ray           beauty = VRayLighting + VRayGlobalIllumination + VRayReflection
//                             + VRayRefraction + VRaySpecular + VRaySelfIllumination + VRaySSS2
//                             + VRayCaustics + VRayBackground (short names "lighting", "GI", ...
//                             as well); VRayRaw* x VRayDiffuseFilter where only the raw one is.
// A family the file does not hold at all is left out (the scene had none, or the renderer did not
// write it: the recomposition error then says so); a family written only in part is listed in
// PassRecipe::missing. Light groups are used only when a file has no light passes (both at once
// would count the light twice).
#include "io_internal.h"

#include <algorithm>

namespace afn::io {
namespace {

/// One way a family is written: the light passes that add up to it, and their factor.
struct Alternative {
    std::vector<std::string> lights;
    std::string factor;
};
/// A term of the formula: the first alternative the file holds completely is used.
using Family = std::vector<Alternative>;

struct Recipe {
    std::string renderer;
    std::string beauty; ///< the beauty's name in the formula text
    std::vector<Family> families;
    std::string groupPrefix; ///< light groups: layers named <prefix><group>
};

const std::vector<Recipe>& recipes()
{
    static const std::vector<Recipe> table = {
        { "blender", "Combined",
            { { { { "DiffDir", "DiffInd" }, "DiffCol" } },
                { { { "GlossDir", "GlossInd" }, "GlossCol" } },
                { { { "TransDir", "TransInd" }, "TransCol" } }, { { { "Emit" }, "" } },
                { { { "Env" }, "" } }, { { { "VolumeDir", "VolumeInd" }, "" } } },
            "Combined_" },
        { "arnold", "RGBA",
            { { { { "diffuse_direct", "diffuse_indirect" }, "" }, { { "diffuse" }, "" } },
                { { { "specular_direct", "specular_indirect" }, "" }, { { "specular" }, "" } },
                { { { "transmission_direct", "transmission_indirect" }, "" },
                    { { "transmission" }, "" } },
                { { { "sss_direct", "sss_indirect" }, "" }, { { "sss" }, "" } },
                { { { "coat_direct", "coat_indirect" }, "" }, { { "coat" }, "" } },
                { { { "sheen_direct", "sheen_indirect" }, "" }, { { "sheen" }, "" } },
                { { { "volume_direct", "volume_indirect" }, "" }, { { "volume" }, "" } },
                { { { "emission" }, "" } }, { { { "background" }, "" } } },
            "RGBA_" },
        // Arnold's built-in LPEs split another way: direct (C[DSV]L) + indirect + emission
        // (C[LO]) + background (CB); used where a file holds these rather than the families.
        { "arnold", "RGBA",
            { { { { "direct" }, "" } }, { { { "indirect" }, "" } }, { { { "emission" }, "" } },
                { { { "background" }, "" } } },
            "RGBA_" },
        { "vray", "RGB",
            { { { { "VRayLighting" }, "" }, { { "lighting" }, "" },
                  { { "VRayRawLighting" }, "VRayDiffuseFilter" } },
                { { { "VRayGlobalIllumination" }, "" }, { { "GI" }, "" },
                    { { "VRayRawGlobalIllumination" }, "VRayDiffuseFilter" } },
                { { { "VRayReflection" }, "" }, { { "reflect" }, "" } },
                { { { "VRayRefraction" }, "" }, { { "refract" }, "" } },
                { { { "VRaySpecular" }, "" }, { { "specular" }, "" } },
                { { { "VRaySelfIllumination" }, "" }, { { "selfIllum" }, "" } },
                { { { "VRaySSS2" }, "" }, { { "SSS" }, "" } },
                { { { "VRayCaustics" }, "" }, { { "caustics" }, "" } },
                { { { "VRayBackground" }, "" }, { { "background" }, "" } } },
            "" },
    };
    return table;
}

const std::vector<std::vector<std::string>> kComps
    = { { "R", "G", "B" }, { "r", "g", "b" }, { "red", "green", "blue" } };

/// The layer the colour's channels belong to, without its pass ("ViewLayer" of
/// "ViewLayer.Combined.R"): passes of the same view layer are preferred.
std::string colorPrefix(const RoleMapping& mapping)
{
    const RoleChannels* color = mapping.find(Role::Color);
    if (!color || color->channels.empty())
        return "";
    const std::string layer = detail::splitLast(color->channels[0]).first;
    return detail::splitLast(layer).first;
}

/// Where the pass `name` lives: "<prefix>.<name>.R,G,B", "<name>.R,G,B", any "<x>.<name>.R,G,B", or
/// a part named `name` holding bare R,G,B.
std::optional<LightPass> locate(
    const FileInfo& info, const std::string& name, const std::string& prefix)
{
    std::vector<std::string> wanted;
    if (!prefix.empty())
        wanted.push_back(prefix + "." + name);
    wanted.push_back(name);
    auto tryLayer = [&](int s, const std::string& layer) -> std::optional<LightPass> {
        const std::vector<std::string>& ch = info.subimages[s].channels;
        for (const auto& comps : kComps) {
            LightPass p { name, s, {}, {}, "" };
            for (const std::string& c : comps) {
                const std::string full = layer.empty() ? c : layer + "." + c;
                auto it = std::find(ch.begin(), ch.end(), full);
                if (it == ch.end())
                    break;
                p.channels.push_back(full);
                p.indices.push_back(static_cast<int>(it - ch.begin()));
            }
            if (p.indices.size() == 3)
                return p;
        }
        return std::nullopt;
    };
    const int n = static_cast<int>(info.subimages.size());
    for (const std::string& layer : wanted)
        for (int s = 0; s < n; ++s)
            if (auto p = tryLayer(s, layer))
                return p;
    for (int s = 0; s < n; ++s) {
        for (const std::string& c : info.subimages[s].channels) {
            const std::string layer = detail::splitLast(c).first;
            if (layer.size() > name.size() + 1
                && layer.compare(layer.size() - name.size() - 1, std::string::npos, "." + name)
                    == 0)
                if (auto p = tryLayer(s, layer))
                    return p;
        }
        if (n > 1 && info.subimages[s].name == name)
            if (auto p = tryLayer(s, ""))
                return p;
    }
    return std::nullopt;
}

void addFactor(PassRecipe& r, const LightPass& factor)
{
    if (!r.find(factor.name)
        && std::none_of(r.factors.begin(), r.factors.end(),
            [&](const LightPass& f) { return f.name == factor.name; }))
        r.factors.push_back(factor);
}

/// The formula text of a recipe as found ("Combined = (DiffDir + DiffInd) x DiffCol + Emit").
std::string formulaText(const std::string& beauty, const PassRecipe& r)
{
    std::string text = beauty + " =";
    for (std::size_t i = 0; i < r.lights.size();) {
        const std::string& factor = r.lights[i].factor;
        std::size_t j = i + 1;
        while (!factor.empty() && j < r.lights.size() && r.lights[j].factor == factor)
            ++j;
        std::string term;
        for (std::size_t k = i; k < j; ++k)
            term += (k > i ? " + " : "") + r.lights[k].name;
        if (!factor.empty())
            term = (j - i > 1 ? "(" + term + ")" : term) + " x " + factor;
        text += (i > 0 ? " + " : " ") + term;
        i = j;
    }
    return text;
}

PassRecipe fromOverride(
    const FileInfo& info, const std::vector<std::string>& names, const std::string& prefix)
{
    PassRecipe r;
    r.renderer = "--aov lights";
    for (const std::string& item : names) {
        const auto star = item.find('*');
        const std::string light = item.substr(0, star);
        const std::string factor = star == std::string::npos ? "" : item.substr(star + 1);
        std::optional<LightPass> p = locate(info, light, prefix);
        if (!p)
            throw IoError("--aov lights: no layer '" + light + "' with R,G,B channels in the file");
        if (!factor.empty()) {
            std::optional<LightPass> f = locate(info, factor, prefix);
            if (!f)
                throw IoError(
                    "--aov lights: no factor layer '" + factor + "' with R,G,B in the file");
            p->factor = factor;
            addFactor(r, *f);
        }
        r.lights.push_back(*p);
    }
    r.formula = formulaText("beauty", r);
    return r;
}

/// The light groups of a file (<prefix><group> layers), as a recipe.
PassRecipe lightGroups(const FileInfo& info, const Recipe& recipe, const std::string& prefix)
{
    PassRecipe r;
    r.renderer = recipe.renderer;
    if (recipe.groupPrefix.empty())
        return r;
    for (int s = 0; s < static_cast<int>(info.subimages.size()); ++s)
        for (const std::string& c : info.subimages[s].channels) {
            std::string layer = detail::splitLast(c).first;
            if (!prefix.empty() && layer.rfind(prefix + ".", 0) == 0)
                layer = layer.substr(prefix.size() + 1);
            if (layer.rfind(recipe.groupPrefix, 0) != 0 || layer.size() == recipe.groupPrefix.size()
                || r.find(layer))
                continue;
            if (std::optional<LightPass> p = locate(info, layer, prefix))
                r.lights.push_back(*p);
        }
    r.formula = formulaText(recipe.beauty, r);
    return r;
}

} // namespace

const LightPass* PassRecipe::find(const std::string& name) const
{
    for (const LightPass& p : lights)
        if (p.name == name)
            return &p;
    for (const LightPass& p : factors)
        if (p.name == name)
            return &p;
    return nullptr;
}

PassRecipe findLightPasses(
    const FileInfo& info, const RoleMapping& mapping, const MappingOverrides& overrides)
{
    const std::string prefix = colorPrefix(mapping);
    if (overrides.lights)
        return fromOverride(info, *overrides.lights, prefix);
    // Every recipe is tried (a file of an unrecognised renderer may still use one of these naming
    // schemes); the one that finds the most passes wins, the file's renderer's on a tie.
    PassRecipe best;
    for (const Recipe& recipe : recipes()) {
        PassRecipe r;
        r.renderer = recipe.renderer;
        for (const Family& family : recipe.families) {
            bool used = false;
            std::vector<std::string> partial;
            for (const Alternative& alt : family) {
                std::vector<LightPass> found;
                for (const std::string& name : alt.lights)
                    if (std::optional<LightPass> p = locate(info, name, prefix))
                        found.push_back(*p);
                std::optional<LightPass> factor;
                if (!alt.factor.empty())
                    factor = locate(info, alt.factor, prefix);
                const bool complete
                    = found.size() == alt.lights.size() && (alt.factor.empty() || factor);
                if (complete) {
                    for (LightPass& p : found) {
                        p.factor = alt.factor;
                        r.lights.push_back(p);
                    }
                    if (factor)
                        addFactor(r, *factor);
                    used = true;
                    break;
                }
                if (!found.empty() && partial.empty()) {
                    for (const std::string& name : alt.lights)
                        if (!locate(info, name, prefix))
                            partial.push_back(name);
                    if (!alt.factor.empty() && !factor)
                        partial.push_back(alt.factor);
                }
            }
            if (!used)
                r.missing.insert(r.missing.end(), partial.begin(), partial.end());
        }
        if (r.lights.empty())
            r = lightGroups(info, recipe, prefix);
        else
            r.formula = formulaText(recipe.beauty, r);
        const bool preferred = recipe.renderer == mapping.renderer;
        if (r.lights.size() > best.lights.size()
            || (preferred && r.lights.size() == best.lights.size() && !r.lights.empty()))
            best = r;
    }
    return best;
}

} // namespace afn::io
