// SPDX-License-Identifier: Apache-2.0
// otherLayerTiles: the layers no role reads, each shown by what its channels look like.
#include "contact_sheet_layers.h"

#include <algorithm>
#include <cmath>
#include <map>

namespace afntool {

namespace {

bool endsWith(const std::string& s, const std::string& suffix)
{
    return s.size() >= suffix.size()
        && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

std::string layerOf(const std::string& channel)
{
    const std::size_t dot = channel.rfind('.');
    return dot == std::string::npos ? "(top level)" : channel.substr(0, dot);
}

/// makeTile kind for a layer's channels and values (see the header).
const char* kindOf(const std::vector<std::string>& names, const std::vector<float>& px)
{
    if (names.size() >= 3) {
        const bool rgb
            = (endsWith(names[0], "R") && endsWith(names[1], "G") && endsWith(names[2], "B"))
            || (endsWith(names[0], "r") && endsWith(names[1], "g") && endsWith(names[2], "b"));
        if (rgb)
            return "albedo";
        // Unit-range vectors (normals of any kind) keep their sign code n*0.5+0.5; anything else
        // is normalised per axis.
        const bool unitRange = std::all_of(px.begin(), px.end(),
            [](float v) { return !std::isfinite(v) || std::fabs(v) <= 1.001f; });
        return unitRange ? "normal" : "position";
    }
    return names.size() == 2 ? "vector2" : "data";
}

} // namespace

std::vector<afn::color::Tile> otherLayerTiles(const afn::color::ColorManager& cm,
    const afn::io::LayeredImage& all, const std::set<std::string>& roleChannels,
    const std::string& display, const std::string& view)
{
    std::map<std::string, std::vector<int>> layers;
    std::set<std::string> readByRole;
    std::vector<std::string> order;
    for (std::size_t c = 0; c < all.channels.size(); ++c) {
        const std::string layer = layerOf(all.channels[c]);
        if (roleChannels.count(all.channels[c]))
            readByRole.insert(layer);
        if (!layers.count(layer))
            order.push_back(layer);
        layers[layer].push_back(static_cast<int>(c));
    }
    std::vector<afn::color::Tile> tiles;
    const std::size_t npx = static_cast<std::size_t>(all.width) * all.height;
    for (const std::string& layer : order) {
        if (readByRole.count(layer))
            continue;
        const std::vector<int>& idx = layers[layer];
        const int comps = static_cast<int>(std::min<std::size_t>(idx.size(), 3));
        std::vector<std::string> names;
        for (int c = 0; c < comps; ++c)
            names.push_back(all.channels[idx[c]]);
        std::vector<float> px(npx * comps);
        for (std::size_t i = 0; i < npx; ++i)
            for (int c = 0; c < comps; ++c)
                px[i * comps + c] = all.pixels[i * all.channels.size() + idx[c]];
        tiles.push_back(afn::color::makeTile(
            cm, kindOf(names, px), layer, all.width, all.height, comps, px.data(), display, view));
    }
    return tiles;
}

} // namespace afntool
