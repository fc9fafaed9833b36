// SPDX-License-Identifier: Apache-2.0
// Contact-sheet tiles of the layers of a file that no role reads.
#pragma once

#include "afn/color.hpp"
#include "afn/io.hpp"

#include <set>
#include <string>
#include <vector>

namespace afntool {

/// One tile per layer (channels grouped by the name before their last '.'; top-level channels
/// form "(top level)") of which no channel is in `roleChannels`: a layer a role reads part of
/// (Blender's Vector: X,Y are motion, Z,W unused) is already shown by that role's tile.
/// How a layer is shown, chosen by its channels:
///   R,G,B (3 or more channels, first ones ending in R, G, B): colour through the display view;
///   3 or more other channels: the first three; as a normal (n*0.5+0.5) when every value is in
///   [-1, 1], else each normalised by its own finite range;
///   2 channels: a 2D vector, hue = direction, brightness = magnitude, with a direction legend;
///   1 channel: grey, normalised by its finite range.
/// Data tiles carry their value range in the label (makeTile). Throws afn::color::ColorError.
std::vector<afn::color::Tile> otherLayerTiles(const afn::color::ColorManager& cm,
    const afn::io::LayeredImage& all, const std::set<std::string>& roleChannels,
    const std::string& display, const std::string& view);

} // namespace afntool
