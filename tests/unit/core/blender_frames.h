// SPDX-License-Identifier: Apache-2.0
// The bundled Blender sequence (examples/sequence: 8 frames, 320x180, 1 spp, with 2048-spp
// references) read with OpenImageIO directly (channels by name), independent of afn_io, for the
// tests that run engines on real renders. Its motion vectors point to the previous frame in pixels
// with y up (motion.yUp=1); normals are world space, depth planar, positions world metres.
#pragma once

#include "base/image.h"

#include <OpenImageIO/imageio.h>

#include <cstdio>
#include <string>
#include <vector>

namespace afntest {

/// Channels `names` of `path` (all in subimage 0) as an image; empty image if unreadable.
inline afn::Image readChannels(const std::string& path, const std::vector<std::string>& names)
{
    auto in = OIIO::ImageInput::open(path);
    if (!in)
        return afn::Image();
    const OIIO::ImageSpec& spec = in->spec();
    std::vector<float> all(static_cast<std::size_t>(spec.width) * spec.height * spec.nchannels);
    if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, all.data()))
        return afn::Image();
    afn::Image img(spec.width, spec.height, static_cast<int>(names.size()));
    for (std::size_t c = 0; c < names.size(); ++c) {
        const int idx = spec.channelindex(names[c]);
        if (idx < 0)
            return afn::Image();
        for (int p = 0; p < spec.width * spec.height; ++p)
            img.data()[p * names.size() + c]
                = all[static_cast<std::size_t>(p) * spec.nchannels + idx];
    }
    return img;
}

/// Blender's channel names of a pass's components, e.g. layer("Normal", "XYZ").
inline std::vector<std::string> layer(const std::string& pass, const char* comps)
{
    std::vector<std::string> v;
    for (const char* c = comps; *c; ++c)
        v.push_back("ViewLayer." + pass + "." + std::string(1, *c));
    return v;
}

/// The passes of one frame of the bundled sequence (empty images where unreadable).
struct BlenderFrame {
    afn::Image color, albedo, normal, depth, position, motion, reference;
};

/// Frame k of examples/sequence (`examplesDir` = AFN_EXAMPLES_DIR).
inline BlenderFrame readBlenderFrame(const std::string& examplesDir, int k)
{
    char name[64];
    std::snprintf(name, sizeof name, "/sequence/frame.%04d.exr", k);
    const std::string path = examplesDir + name;
    BlenderFrame f;
    f.color = readChannels(path, layer("Combined", "RGB"));
    f.albedo = readChannels(path, layer("Denoising Albedo", "RGB"));
    f.normal = readChannels(path, layer("Normal", "XYZ"));
    f.depth = readChannels(path, layer("Depth", "Z"));
    f.position = readChannels(path, layer("Position", "XYZ"));
    f.motion = readChannels(path, layer("Vector", "XY"));
    std::snprintf(name, sizeof name, "/sequence/reference.%04d.exr", k);
    f.reference = readChannels(examplesDir + name, layer("Combined", "RGB"));
    return f;
}

} // namespace afntest
