// SPDX-License-Identifier: Apache-2.0
// Random inputs of the AFN network (methods/afn/network.h Inputs) for the engine tests: uniform
// values, 1-spp colour in [0, 4), accumulation in [0, 2), albedo, normal and depth in [0, 1), drawn
// in that order from one mt19937 seeded by the caller.
#pragma once

#include "base/image.h"
#include "methods/afn/network.h"

#include <cstddef>
#include <random>

namespace afntest {

struct RandomAfnInputs {
    afn::Image c1, cta, albedo, normal, depth;
    afn::afnet::Inputs in; ///< points at the images above

    RandomAfnInputs(int w, int h, unsigned seed)
    {
        std::mt19937 rng(seed);
        std::uniform_real_distribution<float> u(0.0f, 1.0f);
        auto fill = [&](afn::Image& img, int c, float scale) {
            img = afn::Image(w, h, c);
            for (std::size_t k = 0; k < img.size(); ++k)
                img.data()[k] = scale * u(rng);
        };
        fill(c1, 3, 4.0f), fill(cta, 3, 2.0f), fill(albedo, 3, 1.0f), fill(normal, 3, 1.0f);
        fill(depth, 1, 1.0f);
        in = { &c1, &cta, &albedo, &normal, &depth };
    }
    RandomAfnInputs(const RandomAfnInputs&) = delete; // `in` would point into the original
    RandomAfnInputs& operator=(const RandomAfnInputs&) = delete;
};

} // namespace afntest
