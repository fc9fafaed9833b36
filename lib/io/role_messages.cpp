// SPDX-License-Identifier: Apache-2.0
// What the role mapping tells the user about a role it did not find: the names it actually tried
// (the chosen preset's, then the generic ones; every preset's only when no preset found a colour)
// and the file's own channels, grouped by layer so that a 40-channel Blender file stays one line.
#include "io_internal.h"

#include <algorithm>

namespace afn::io::detail {
namespace {

void addUnique(std::vector<std::string>& out, const std::string& s)
{
    if (std::find(out.begin(), out.end(), s) == out.end())
        out.push_back(s);
}

std::string join(const std::vector<std::string>& v, const std::string& sep)
{
    std::string out;
    for (std::size_t i = 0; i < v.size(); ++i)
        out += (i ? sep : "") + v[i];
    return out;
}

/// The Blender view layer the colour was found in ("" when unknown or not Blender).
std::string viewLayerOf(const RoleMapping& mapping)
{
    const RoleChannels* c = mapping.find(Role::Color);
    if (!c || c->channels.empty() || mapping.renderer != "blender")
        return {};
    return splitLast(splitLast(c->channels.front()).first).first;
}

} // namespace

void addTriedNames(
    const Preset& preset, Role role, const RoleMapping& mapping, std::vector<std::string>& out)
{
    // A candidate as one would name it in --aov: a layer (matched by suffix, so Blender's
    // "<view layer>.Denoising Albedo" is written with the colour's view layer when it is known),
    // or the top-level channels ("R,G,B", "Z").
    const std::string viewLayer = preset.renderer == "blender" ? viewLayerOf(mapping) : "";
    for (const RoleCandidates& rc : preset.roles) {
        if (rc.role != role)
            continue;
        for (const Candidate& cand : rc.candidates) {
            if (!cand.layer.empty())
                addUnique(out, viewLayer.empty() ? cand.layer : viewLayer + "." + cand.layer);
            else if (!cand.comps.empty())
                addUnique(out, join(cand.comps.front(), ","));
        }
    }
}

std::string channelSummary(const FileInfo& info, std::size_t maxLayers)
{
    // "<layer> (<components>)" per layer in the order stored; parts of multi-part files are
    // prefixed with the part name, top-level channels are listed by name.
    std::vector<std::string> order;
    std::vector<std::vector<std::string>> comps;
    const bool multi = info.subimages.size() > 1;
    for (const SubimageInfo& si : info.subimages)
        for (const std::string& ch : si.channels) {
            auto [layer, comp] = splitLast(ch);
            if (multi && !si.name.empty())
                layer = layer.empty() ? si.name : si.name + "." + layer;
            auto it = std::find(order.begin(), order.end(), layer);
            if (it == order.end()) {
                order.push_back(layer);
                comps.emplace_back();
                it = order.end() - 1;
            }
            comps[static_cast<std::size_t>(it - order.begin())].push_back(comp);
        }
    std::vector<std::string> items;
    for (std::size_t i = 0; i < order.size() && items.size() < maxLayers; ++i)
        items.push_back(
            order[i].empty() ? join(comps[i], ", ") : order[i] + " (" + join(comps[i], ",") + ")");
    std::string text = items.empty() ? "no channels" : join(items, ", ");
    if (order.size() > items.size())
        text += ", ... (" + std::to_string(order.size() - items.size()) + " more layers)";
    return text;
}

std::string missingRoleMessage(Role role, const RoleMapping& mapping, const std::string& channels)
{
    std::string msg = std::string("no ") + roleName(role) + " channels found";
    auto it = mapping.lookedFor.find(role);
    if (it != mapping.lookedFor.end() && !it->second.empty())
        msg += "; tried " + join(it->second, "; ");
    if (!channels.empty())
        msg += "; the file has: " + channels;
    msg += " (use --aov " + std::string(roleName(role)) + "=<channels> to name them)";
    return msg;
}

} // namespace afn::io::detail
