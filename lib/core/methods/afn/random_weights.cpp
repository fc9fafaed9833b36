// SPDX-License-Identifier: Apache-2.0
// Random AFN weights (see methods/afn/random_weights.h).
#include "methods/afn/random_weights.h"

#include <cmath>
#include <random>

namespace afn::afnet {

nn::WeightsArchive randomWeights(const Architecture& a, unsigned seed)
{
    std::mt19937 rng(seed);
    std::map<std::string, nn::WeightTensor> t;
    auto conv = [&](const std::string& name, int in, int out, int k) {
        const float bound = 1.0f / std::sqrt(static_cast<float>(in * k * k));
        std::uniform_real_distribution<float> u(-bound, bound);
        nn::WeightTensor w, b;
        w.dims = { out, in, k, k };
        w.data.resize(static_cast<std::size_t>(out) * in * k * k);
        for (float& v : w.data)
            v = u(rng);
        b.dims = { out };
        b.data.resize(out);
        for (float& v : b.data)
            v = u(rng);
        t[name + ".weight"] = std::move(w);
        t[name + ".bias"] = std::move(b);
    };
    conv("enc1", 13, a.enc[0], 3);
    conv("enc2", a.enc[0], a.enc[1], 3);
    conv("enc3", a.enc[1], a.enc[2], 3);
    conv("dec2", a.enc[2] + a.enc[1], a.dec[0], 3);
    conv("dec1", a.dec[0] + a.enc[0], a.dec[1], 3);
    conv("head1", a.dec[1], 49, 1);
    conv("headTA", a.dec[1] + 13, 50, 1);
    if (a.variant == "full") {
        conv("ref1", 10, a.refine, 3);
        conv("ref2", a.refine, a.refine, 3);
        conv("ref3", a.refine, 3, 3);
    }
    std::map<std::string, std::string> meta { { "variant", a.variant } };
    if (a.albedoTrust) { // drawn last: the other tensors are those of the same seed without it
        conv("headG", a.enc[0], 1, 3);
        meta["albedoTrust"] = "1";
    }
    return nn::WeightsArchive::fromTensors(std::move(t), std::move(meta), "random weights");
}

} // namespace afn::afnet
