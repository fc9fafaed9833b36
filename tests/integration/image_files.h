// SPDX-License-Identifier: Apache-2.0
// Making and reading test images with OpenImageIO directly (not through afn_io), so that what
// afntool writes is checked by an independent reader.
#pragma once

#include <OpenImageIO/imageio.h>

#include <cmath>
#include <string>
#include <vector>

/// Write `pixels` (float, spec.nchannels per pixel, data window size) in the spec's format.
inline bool writeImage(
    const std::string& path, const OIIO::ImageSpec& spec, const std::vector<float>& pixels)
{
    auto out = OIIO::ImageOutput::create(path);
    return out && out->open(path, spec) && out->write_image(OIIO::TypeFloat, pixels.data())
        && out->close();
}

/// A file's spec and pixels (float); empty pixels when it cannot be read.
struct ReadBack {
    OIIO::ImageSpec spec;
    std::vector<float> pixels;
};

inline ReadBack readImage(const std::string& path)
{
    ReadBack r;
    auto in = OIIO::ImageInput::open(path);
    if (!in)
        return r;
    r.spec = in->spec();
    r.pixels.resize(static_cast<size_t>(r.spec.width) * r.spec.height * r.spec.nchannels);
    if (!in->read_image(0, 0, 0, r.spec.nchannels, OIIO::TypeFloat, r.pixels.data()))
        r.pixels.clear();
    return r;
}

/// The sRGB transfer function (IEC 61966-2-1), encoded value -> linear.
inline float srgbToLinear(float v)
{
    return v <= 0.04045f ? v / 12.92f : std::pow((v + 0.055f) / 1.055f, 2.4f);
}
