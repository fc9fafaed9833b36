// SPDX-License-Identifier: Apache-2.0
// "wskpn": the weight-sharing kernel-prediction denoiser (Fan et al. 2021), one of the paper's
// learned baselines. Per frame, after the shared stages (aux prefilter, demodulation, BMFR
// temporal accumulation: the same TA-1spp colour afn reads): the 10-channel input
// (nn/baseline_input.h), the folded network and the weight-sharing filter (network.h), then
// remodulation by the albedo. Weights: the archive embedded at build time (weights/wskpn.afnw,
// trained with training/afn/baselines/train.py) or afnSetFilterData(filter, "weights", ...).
// The filter itself is nn/baseline_filter.h, shared with nbgd; this file gives the network.
#include "methods/wskpn/network.h"
#include "nn/baseline_filter.h"

#ifdef AFN_HAS_WSKPN_WEIGHTS
extern "C" const unsigned char wskpnEmbeddedWeights[];
extern "C" const unsigned long long wskpnEmbeddedWeights_size;
#endif

namespace afn::wskpn {

namespace {

nn::EmbeddedWeights embeddedWeights()
{
#ifdef AFN_HAS_WSKPN_WEIGHTS
    return { wskpnEmbeddedWeights, static_cast<std::size_t>(wskpnEmbeddedWeights_size) };
#else
    return {};
#endif
}

class WskpnFilter final : public nn::BaselineFilter<Network> {
public:
    explicit WskpnFilter(const FilterType& t)
        : BaselineFilter(t, "WSKPN", embeddedWeights())
    {
    }
};

} // namespace

FilterType filterType()
{
    FilterType t = nn::baselineFilterType("wskpn",
        "Weight-sharing kernel prediction (Fan et al. 2021): learned per-pixel weights "
        "shared over six box windows on the temporal accumulation",
        embeddedWeights().data != nullptr);
    t.create = factoryOf<WskpnFilter>();
    return t;
}

} // namespace afn::wskpn
