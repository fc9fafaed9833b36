// SPDX-License-Identifier: Apache-2.0
// "onnd": the recurrent denoising autoencoder of Chaitanya et al. 2017 (the paper's baseline
// ONND). Per frame, after the shared stages: scale normal and depth, run the recurrent network
// (network.h) and remodulate (methods/ta_network_filter.h, shared with mrkp). The recurrent state
// is the filter's history: kept between executes, dropped by afnResetFilter, a frame-size change
// or new weights. Weights: the archive embedded at build time (weights/onnd.afnw), or
// afnSetFilterData(filter, "weights", ...).
#include "methods/onnd/network.h"
#include "methods/ta_network_filter.h"

#ifdef AFN_HAS_ONND_WEIGHTS
extern "C" const unsigned char onndEmbeddedWeights[];
extern "C" const unsigned long long onndEmbeddedWeights_size;
#endif

namespace afn::onnd {

namespace {

nn::EmbeddedWeights embeddedWeights()
{
#ifdef AFN_HAS_ONND_WEIGHTS
    return { onndEmbeddedWeights, static_cast<std::size_t>(onndEmbeddedWeights_size) };
#else
    return {};
#endif
}

class OnndFilter final : public TaNetworkFilter<Network> {
public:
    explicit OnndFilter(const FilterType& t)
        : TaNetworkFilter(t, { "onnd", "ONND" }, embeddedWeights())
    {
    }

private:
    void resetHistory() override { m_net.resetState(); }
};

} // namespace

FilterType filterType()
{
    FilterType t = taNetworkFilterType("onnd",
        "recurrent denoising autoencoder (Chaitanya et al. 2017, the paper's ONND "
        "baseline) on the TA-accumulated frame",
        embeddedWeights().data != nullptr);
    t.create = factoryOf<OnndFilter>();
    return t;
}

} // namespace afn::onnd
