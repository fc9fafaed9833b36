// SPDX-License-Identifier: Apache-2.0
// Map channel names to roles: pick the renderer convention that explains the file best, then apply
// the user's overrides. Channels are always looked up by name, never by position.
#include "io_internal.h"

#include <algorithm>
#include <cctype>
#include <set>

namespace afn::io {
namespace {

using detail::Candidate;
using detail::Preset;

/// The --aov value that unbinds a role ("--aov depth=none").
const std::string kNoChannels = "none";

/// One channel as seen by the matcher. Channels of named parts in multi-part files are also
/// visible under "<part>.<layer>" (a part "albedo" holding R,G,B is the layer "albedo").
struct Entry {
    int sub = 0;
    int index = 0;
    std::string name; ///< as stored
    std::string qualified; ///< "<part>.<name>" in multi-part files, else the name
    std::string layer;
    std::string comp;
};

struct Match {
    int sub = 0;
    std::string layer; ///< full layer (or the channel name for a bare single channel)
    std::vector<int> indices;
    std::vector<std::string> names;
};

std::string lower(std::string s)
{
    for (char& c : s)
        c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return s;
}

bool endsWith(const std::string& s, const std::string& suffix)
{
    return s.size() >= suffix.size()
        && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

bool beautyPartName(const std::string& name)
{
    static const char* const names[] = { "rgba", "rgb", "beauty", "main", "default", "c", "ci" };
    const std::string n = lower(name);
    for (const char* b : names)
        if (n == b)
            return true;
    return false;
}

/// The part whose bare channels (R, G, B, ...) count as top-level: one with a beauty-like name
/// ("rgba", "beauty", ...), else the first part.
int topLevelPart(const FileInfo& info)
{
    for (int s = 0; s < static_cast<int>(info.subimages.size()); ++s)
        if (beautyPartName(info.subimages[s].name))
            return s;
    return 0;
}

std::vector<Entry> buildEntries(const FileInfo& info)
{
    std::vector<Entry> entries;
    const bool multi = info.subimages.size() > 1;
    const int top = topLevelPart(info);
    for (int s = 0; s < static_cast<int>(info.subimages.size()); ++s) {
        const SubimageInfo& si = info.subimages[s];
        for (int i = 0; i < static_cast<int>(si.channels.size()); ++i) {
            Entry e;
            e.sub = s;
            e.index = i;
            e.name = si.channels[i];
            e.qualified = multi && !si.name.empty() ? si.name + "." + e.name : e.name;
            std::tie(e.layer, e.comp) = detail::splitLast(e.name);
            // Bare channels of other named parts belong to that part's layer only.
            if (!(multi && s != top && e.layer.empty() && !si.name.empty()))
                entries.push_back(e);
            if (multi && !si.name.empty()) {
                e.layer = e.layer.empty() ? si.name : si.name + "." + e.layer;
                entries.push_back(e);
            }
        }
    }
    return entries;
}

bool layerMatches(const std::string& layer, const std::string& want)
{
    if (layer == want)
        return true;
    return !want.empty() && layer.size() > want.size() && endsWith(layer, "." + want);
}

std::optional<Match> matchCandidate(
    const std::vector<Entry>& entries, const Candidate& cand, int ncomp, const std::string& prefix)
{
    // A single-component role may be a bare top-level channel named like the layer ("zDepth").
    if (ncomp == 1 && !cand.layer.empty())
        for (const Entry& e : entries)
            if (e.layer.empty() && e.comp == cand.layer)
                return Match { e.sub, e.name, { e.index }, { e.name } };

    std::vector<std::pair<int, std::string>> layers;
    for (const Entry& e : entries)
        if (layerMatches(e.layer, cand.layer)
            && std::find(layers.begin(), layers.end(), std::make_pair(e.sub, e.layer))
                == layers.end())
            layers.emplace_back(e.sub, e.layer);
    // Exact name first, then the view layer the colour came from, then anything but Blender's
    // compositor output ("Composite.Combined").
    auto rank = [&](const std::string& l) {
        if (l == cand.layer)
            return 0;
        if (!prefix.empty() && l == prefix + "." + cand.layer)
            return 1;
        return l.rfind("Composite.", 0) == 0 ? 3 : 2;
    };
    std::stable_sort(layers.begin(), layers.end(),
        [&](const auto& a, const auto& b) { return rank(a.second) < rank(b.second); });

    for (const auto& subLayer : layers) {
        // Named copies: lambdas may not capture structured bindings in C++17.
        const int sub = subLayer.first;
        const std::string& layer = subLayer.second;
        for (const std::vector<std::string>& comps : cand.comps) {
            Match m { sub, layer, {}, {} };
            for (const std::string& c : comps) {
                auto it = std::find_if(entries.begin(), entries.end(), [&](const Entry& e) {
                    return e.sub == sub && e.layer == layer && e.comp == c;
                });
                if (it == entries.end())
                    break;
                m.indices.push_back(it->index);
                m.names.push_back(it->name);
            }
            if (m.indices.size() == comps.size())
                return m;
        }
    }
    return std::nullopt;
}

struct Evaluated {
    RoleMapping mapping;
    int specific = 0; ///< roles found through renderer-specific names
    bool hasColor = false;
};

Evaluated evaluate(const std::vector<Entry>& entries, const Preset& preset)
{
    Evaluated ev;
    ev.mapping.renderer = preset.renderer;
    ev.mapping.tag = preset.tag;
    std::string prefix; // Blender view layer, learnt from the colour
    for (const detail::RoleCandidates& rc : preset.roles) {
        for (const Candidate& cand : rc.candidates) {
            const auto m = matchCandidate(entries, cand, roleComponents(rc.role), prefix);
            if (!m)
                continue;
            ev.mapping.roles.push_back(
                { rc.role, m->sub, m->names, m->indices, preset.label + " '" + m->layer + "'" });
            for (const auto& [k, v] : cand.tags)
                detail::applyTag(ev.mapping.tag, k, v);
            if (!cand.generic)
                ++ev.specific;
            if (rc.role == Role::Color) {
                ev.hasColor = true;
                if (!cand.layer.empty() && m->layer != cand.layer && endsWith(m->layer, cand.layer))
                    prefix = m->layer.substr(0, m->layer.size() - cand.layer.size() - 1);
            }
            break;
        }
    }
    return ev;
}

bool hinted(const Preset& preset, const std::map<std::string, std::string>& attributes)
{
    for (const auto& [name, value] : attributes) {
        const std::string n = lower(name), v = lower(value);
        for (const std::string& h : preset.attributeHints) {
            if (n.rfind(h, 0) == 0)
                return true;
            if ((n == "software" || n == "renderer" || n == "creator")
                && v.find(h) != std::string::npos)
                return true;
        }
    }
    return false;
}

std::string join(const std::vector<std::string>& v, const std::string& sep)
{
    std::string out;
    for (std::size_t i = 0; i < v.size(); ++i)
        out += (i ? sep : "") + v[i];
    return out;
}

/// Roles the chosen preset left unmapped, filled from the generic preset's names ("albedo",
/// "N", "P", top-level "Z", "motionvector", ...). A hinted preset (e.g. a file Blender wrote)
/// may hold passes a compositor or a script named generically; without this fallback such a
/// file mapped nothing but the colour. The chosen preset's conventions stay in effect (the
/// generic names carry none); mapRoles warns that they are assumed. Returns the roles added.
std::vector<Role> addGenericFallback(
    const std::vector<Entry>& entries, const Preset& chosen, RoleMapping& mapping)
{
    std::vector<Role> added;
    const Preset& generic = detail::presets().back();
    if (&chosen == &generic)
        return added;
    const Evaluated ev = evaluate(entries, generic);
    for (const RoleChannels& rc : ev.mapping.roles) {
        if (mapping.find(rc.role))
            continue;
        // A channel already given to another role is not taken twice.
        bool taken = false;
        for (const RoleChannels& have : mapping.roles)
            for (int i : have.indices)
                taken = taken
                    || (have.subimage == rc.subimage
                        && std::find(rc.indices.begin(), rc.indices.end(), i) != rc.indices.end());
        if (taken)
            continue;
        mapping.roles.push_back(rc);
        added.push_back(rc.role);
    }
    return added;
}

/// The names tried for each role left unmapped: the chosen preset's, then the generic ones; a
/// colour nobody found was looked for under every preset's names.
void recordLookedFor(const Preset& chosen, RoleMapping& mapping)
{
    const Preset& generic = detail::presets().back();
    for (int r = 0; r < kNumRoles; ++r) {
        const Role role = static_cast<Role>(r);
        if (mapping.find(role))
            continue;
        std::vector<std::string> tried;
        if (role == Role::Color) {
            for (const Preset& p : detail::presets())
                detail::addTriedNames(p, role, mapping, tried);
        } else {
            detail::addTriedNames(chosen, role, mapping, tried);
            detail::addTriedNames(generic, role, mapping, tried);
        }
        if (!tried.empty())
            mapping.lookedFor[role] = tried;
    }
}

const detail::Preset& choosePreset(
    const std::vector<Entry>& entries, const FileInfo& info, Evaluated& best)
{
    const std::vector<Preset>& all = detail::presets();
    std::vector<Evaluated> evs;
    for (const Preset& p : all)
        evs.push_back(evaluate(entries, p));
    for (std::size_t i = 0; i < all.size(); ++i)
        if (evs[i].hasColor && hinted(all[i], info.attributes)) {
            best = evs[i];
            return all[i];
        }
    // Among presets that find a colour, the most renderer-specific roles wins (ties: the earlier
    // preset; nothing specific: generic, the last). With no colour anywhere, the most specific.
    std::size_t pick = all.size() - 1;
    int bestScore = 0;
    bool anyColor = false;
    for (const Evaluated& e : evs)
        anyColor = anyColor || e.hasColor;
    for (std::size_t i = 0; i < all.size(); ++i)
        if ((evs[i].hasColor || !anyColor) && evs[i].specific > bestScore) {
            bestScore = evs[i].specific;
            pick = i;
        }
    best = evs[pick];
    return all[pick];
}

/// Map `role` to the channels the user named; false when the file has no such channels.
bool applyChannelOverride(const std::vector<Entry>& entries, const Preset& preset, Role role,
    const std::vector<std::string>& names, RoleMapping& mapping)
{
    auto& roles = mapping.roles;
    roles.erase(std::remove_if(roles.begin(), roles.end(),
                    [&](const RoleChannels& r) { return r.role == role; }),
        roles.end());
    const std::string spelled = std::string(roleName(role)) + "=" + join(names, ",");
    std::optional<Match> m;
    const bool oneChannel = roleComponents(role) == 1 || role == Role::Variance;
    if (names.size() > 1 || oneChannel) {
        std::set<int> subs;
        for (const Entry& e : entries)
            subs.insert(e.sub);
        for (int s : subs) {
            Match cur { s, "", {}, {} };
            for (const std::string& n : names) {
                auto it = std::find_if(entries.begin(), entries.end(), [&](const Entry& e) {
                    return e.sub == s && (e.name == n || e.qualified == n);
                });
                if (it == entries.end())
                    break;
                cur.indices.push_back(it->index);
                cur.names.push_back(it->name);
            }
            if (cur.indices.size() == names.size()) {
                m = cur;
                break;
            }
        }
    }
    if (!m && names.size() == 1) {
        // A layer prefix: components by the role's usual names.
        const Role probe = role == Role::Variance ? Role::Color : role;
        Candidate cand;
        cand.layer = names.front();
        for (const Preset& p : detail::presets())
            for (const detail::RoleCandidates& rc : p.roles)
                if (rc.role == probe)
                    for (const Candidate& c : rc.candidates)
                        for (const auto& comps : c.comps)
                            if (std::find(cand.comps.begin(), cand.comps.end(), comps)
                                == cand.comps.end())
                                cand.comps.push_back(comps);
        if (role == Role::Variance)
            cand.comps.push_back({ "Y" }), cand.comps.push_back({ "R" });
        m = matchCandidate(entries, cand, roleComponents(role), "");
    }
    if (!m) {
        mapping.lookedFor[role] = { join(names, ",") };
        return false;
    }
    mapping.lookedFor.erase(role);
    roles.push_back({ role, m->sub, m->names, m->indices, "--aov " + spelled });
    // A pass the preset knows keeps its conventions ("normal=ViewLayer.Denoising Normal" is camera
    // space); explicit tag overrides are applied afterwards and win.
    const std::string layer = detail::splitLast(m->names.front()).first;
    for (const detail::RoleCandidates& rc : preset.roles)
        if (rc.role == role)
            for (const Candidate& cand : rc.candidates)
                if (!cand.layer.empty() && layerMatches(layer, cand.layer)) {
                    for (const auto& [k, v] : cand.tags)
                        detail::applyTag(mapping.tag, k, v);
                    return true;
                }
    return true;
}

} // namespace

RoleMapping mapRoles(const FileInfo& info, const MappingOverrides& overrides)
{
    const std::vector<Entry> entries = buildEntries(info);
    Evaluated ev;
    const Preset& chosen = choosePreset(entries, info, ev);
    RoleMapping mapping = ev.mapping;
    mapping.presetsTried = { chosen.label };
    if (&chosen != &detail::presets().back())
        mapping.presetsTried.push_back(detail::presets().back().label);
    const std::vector<Role> generic = addGenericFallback(entries, chosen, mapping);
    recordLookedFor(chosen, mapping);

    // A mistyped --aov is an error, not a warning: the run would otherwise go on without the
    // role the user asked for.
    for (const auto& [role, names] : overrides.channels) {
        if (names == std::vector<std::string> { kNoChannels }) {
            // "--aov ROLE=none": run as if the file had no such pass (input-aware methods pick
            // the path and weights for what is left; training prepares such inputs this way).
            if (role == Role::Color)
                throw IoError("--aov color=none: the colour is required", info.path);
            auto& roles = mapping.roles;
            const Role absent = role; // a structured binding cannot be captured (C++17, clang)
            roles.erase(std::remove_if(roles.begin(), roles.end(),
                            [absent](const RoleChannels& r) { return r.role == absent; }),
                roles.end());
            mapping.lookedFor.erase(role);
            continue;
        }
        if (!applyChannelOverride(entries, chosen, role, names, mapping))
            throw IoError("--aov " + std::string(roleName(role)) + "=" + join(names, ",")
                    + ": no such channels or layer; the file has: " + detail::channelSummary(info),
                info.path);
    }
    for (const auto& [key, value] : overrides.tags)
        if (!detail::applyTag(mapping.tag, key, value))
            throw IoError("--aov: invalid tag " + key + "=" + value, info.path);
    std::stable_sort(mapping.roles.begin(), mapping.roles.end(),
        [](const RoleChannels& a, const RoleChannels& b) { return a.role < b.role; });

    // Generic names carry no conventions: say which of the preset's are assumed for them.
    std::vector<std::string> assumed;
    for (Role r : generic) {
        const RoleChannels* rc = mapping.find(r);
        if (!rc || rc->source.rfind("--aov", 0) == 0)
            continue;
        for (const auto& [name, value] : mapping.tag.parameters())
            if (name.rfind(std::string(roleName(r)) + ".", 0) == 0 && !overrides.tags.count(name))
                assumed.push_back(name + "=" + value);
    }
    if (!assumed.empty())
        mapping.warnings.push_back("generic channel names in a " + chosen.label + " file: assuming "
            + join(assumed, ", ") + " (set --aov <name>=<value> if wrong)");
    const RoleChannels* color = mapping.find(Role::Color);
    if (color && color->source.find("'Noisy Image'") != std::string::npos)
        mapping.warnings.push_back("using Blender 'Noisy Image' as colour: Combined is denoised");
    const RoleChannels* depth = mapping.find(Role::Depth);
    if (mapping.renderer == "vray" && depth && depth->source.rfind("--aov", 0) != 0)
        mapping.warnings.push_back("V-Ray zDepth is normalised unless written raw");
    const bool motionTagged = overrides.tags.count("motion.direction")
        || overrides.tags.count("motion.yUp") || overrides.tags.count("motion.units");
    const bool motionGeneric = std::find(generic.begin(), generic.end(), Role::Motion)
        != generic.end(); // already in the warning above
    if (mapping.find(Role::Motion) && !motionTagged && !motionGeneric
        && mapping.renderer != "blender" && mapping.renderer != "generic")
        mapping.warnings.push_back("motion conventions of " + mapping.renderer + " are assumed ("
            + mapping.tag.motionDirection + ", y " + (mapping.tag.motionYUp ? "up" : "down")
            + "); set --aov motion.direction=..., motion.yUp=... if wrong");
    return mapping;
}

} // namespace afn::io
