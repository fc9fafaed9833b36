// SPDX-License-Identifier: Apache-2.0
// Shared helpers of afn_io's sources (not installed): renderer presets, channel-name parsing.
#pragma once

#include "afn/io.hpp"

#include <string>
#include <utility>
#include <vector>

namespace afn::io::detail {

/// One way a role may be stored: a layer (matched exactly, or as the last part of a nested layer
/// such as "<view layer>.Denoising Albedo") and sets of component names tried in order.
struct Candidate {
    std::string layer; ///< "" = top-level channels (R, G, B, Z, ...)
    std::vector<std::vector<std::string>> comps; ///< e.g. {{"R","G","B"},{"X","Y","Z"}}
    std::vector<std::pair<std::string, std::string>> tags; ///< tags set when this one is used
    bool generic = false; ///< common to every renderer (does not count for detection)
};

struct RoleCandidates {
    Role role;
    std::vector<Candidate> candidates; ///< in order of preference
};

/// A renderer's naming convention.
struct Preset {
    std::string renderer; ///< RoleMapping::renderer value
    std::string label; ///< for RoleChannels::source ("Blender Cycles")
    std::vector<std::string> attributeHints; ///< header attribute name prefixes that identify it
    SpaceTag tag; ///< default conventions
    std::vector<RoleCandidates> roles;
};

/// Every preset, Blender first, generic last.
const std::vector<Preset>& presets();

/// Split "a.b.c" on the last '.': {"a.b", "c"}; no dot: {"", name}.
std::pair<std::string, std::string> splitLast(const std::string& name);

/// Set one tag by its filter-parameter name; false for an unknown name or value.
bool applyTag(SpaceTag& tag, const std::string& key, const std::string& value);

/// OIIO TypeDesc name -> "half" | "float" | "uint" | other.
std::string typeName(int basetype);

/// Throw IoError if the path does not name an existing regular file.
void requireFile(const std::string& path);

/// Throw IoError when an OpenEXR file declares an attribute larger than the rest of the file
/// (exr_header.cpp); other files pass.
void checkExrHeader(const std::string& path);

/// readFrame for a BMFR pseudo path ("<dir>#bmfr:N"); see bmfr_dataset.cpp.
FrameImages readBmfrFrame(const std::string& dir, int frame, const ReadOptions& options);

/// Append the names `preset` tries for `role` to `out` (once each), as --aov would spell them:
/// layers ("albedo", "ViewLayer.Denoising Albedo") or top-level channels ("R,G,B").
void addTriedNames(
    const Preset& preset, Role role, const RoleMapping& mapping, std::vector<std::string>& out);

/// The file's channels grouped by layer ("ViewLayer.Combined (R,G,B,A), Z"), at most `maxLayers`
/// layers ("... (N more layers)").
std::string channelSummary(const FileInfo& info, std::size_t maxLayers = 24);

/// The IoError message for a required role that was not found: what was tried (lookedFor) and
/// the file's channels (`channels`, e.g. channelSummary(); may be empty).
std::string missingRoleMessage(Role role, const RoleMapping& mapping, const std::string& channels);

} // namespace afn::io::detail
