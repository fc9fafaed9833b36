// SPDX-License-Identifier: Apache-2.0
// A small still frame for the tests that run a learned filter through createFilter: colour
// ((7x + 3y + c) mod 5) * 0.3, albedo 0.5, normal +z, depth 1 + 0.1x, zero motion (bound on
// request), and an output buffer.
#pragma once

#include "base/image.h"
#include "bind_image.h"
#include "filter/filter.h"

namespace afntest {

struct StillFrame {
    afn::Image color, albedo, normal, depth, motion, out;

    StillFrame(int w, int h)
        : color(w, h, 3)
        , albedo(w, h, 3, 0.5f)
        , normal(w, h, 3)
        , depth(w, h, 1)
        , motion(w, h, 2)
        , out(w, h, 3)
    {
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                for (int c = 0; c < 3; ++c)
                    color(x, y, c) = static_cast<float>(((x * 7 + y * 3 + c) % 5)) * 0.3f;
                normal(x, y, 2) = 1.0f;
                depth(x, y, 0) = 1.0f + 0.1f * static_cast<float>(x);
            }
    }

    /// Bind colour, albedo, normal, depth and the output to `f`.
    void bindTo(afn::Filter& f)
    {
        f.setImage("color", bindImage(color));
        f.setImage("albedo", bindImage(albedo));
        f.setImage("normal", bindImage(normal));
        f.setImage("depth", bindImage(depth));
        f.setImage("output", bindImage(out));
    }

    /// Also bind a zero motion (a temporal history): the afn model for every input needs it.
    void bindMotionTo(afn::Filter& f) { f.setImage("motion", bindImage(motion)); }
};

} // namespace afntest
