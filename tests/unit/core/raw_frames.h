// SPDX-License-Identifier: Apache-2.0
// Frames as raw float planes (scripts/dump-gpu-frames.py: the bundled Blender sequence for the GPU
// check, which runs where there is no OpenImageIO). Format, little-endian: "AFNRAW01", int32
// width, int32 height, then color (3), albedo (3), normal (3), depth (1), position (3), motion
// (2), each width * height * channels float32, interleaved.
#pragma once

#include "afn_synthetic_sequence.h"

#include <cstdint>
#include <cstring>
#include <fstream>
#include <string>

namespace afntest {

/// Read `path` into `frame`; false (frame unchanged) when it cannot be read or is not the format.
inline bool readRawFrame(const std::string& path, SequenceFrame& frame)
{
    std::ifstream in(path, std::ios::binary);
    char magic[8];
    std::int32_t size[2];
    if (!in.read(magic, 8) || std::memcmp(magic, "AFNRAW01", 8) != 0
        || !in.read(reinterpret_cast<char*>(size), sizeof size) || size[0] <= 0 || size[1] <= 0
        || size[0] > 16384 || size[1] > 16384)
        return false;
    SequenceFrame f;
    afn::Image* planes[] = { &f.color, &f.albedo, &f.normal, &f.depth, &f.position, &f.motion };
    const int channels[] = { 3, 3, 3, 1, 3, 2 };
    for (int k = 0; k < 6; ++k) {
        *planes[k] = afn::Image(size[0], size[1], channels[k]);
        const std::streamsize bytes
            = static_cast<std::streamsize>(planes[k]->size() * sizeof(float));
        if (!in.read(reinterpret_cast<char*>(planes[k]->data()), bytes))
            return false;
    }
    if (in.peek() != std::ifstream::traits_type::eof())
        return false; // trailing bytes: not this format
    frame = std::move(f);
    return true;
}

} // namespace afntest
