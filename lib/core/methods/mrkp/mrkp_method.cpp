// SPDX-License-Identifier: Apache-2.0
// "mrkp": multi-resolution kernel prediction as defined in the NBGD paper's supplement (the
// paper's MR-KP baseline). Per frame, after the shared stages: scale normal and depth, run the
// network (network.h, kernels.h) and remodulate (methods/ta_network_filter.h, shared with onnd).
// It keeps no history of its own (the temporal accumulation is the shared stage's). Weights: the
// archive embedded at build time (weights/mrkp.afnw), or afnSetFilterData(filter, "weights", ...).
#include "methods/mrkp/network.h"
#include "methods/ta_network_filter.h"

#ifdef AFN_HAS_MRKP_WEIGHTS
extern "C" const unsigned char mrkpEmbeddedWeights[];
extern "C" const unsigned long long mrkpEmbeddedWeights_size;
#endif

namespace afn::mrkp {

namespace {

nn::EmbeddedWeights embeddedWeights()
{
#ifdef AFN_HAS_MRKP_WEIGHTS
    return { mrkpEmbeddedWeights, static_cast<std::size_t>(mrkpEmbeddedWeights_size) };
#else
    return {};
#endif
}

class MrkpFilter final : public TaNetworkFilter<Network> {
public:
    explicit MrkpFilter(const FilterType& t)
        : TaNetworkFilter(t, { "mrkp", "MR-KP" }, embeddedWeights())
    {
    }
};

} // namespace

FilterType filterType()
{
    FilterType t = taNetworkFilterType("mrkp",
        "multi-resolution kernel prediction (KPCN with level blending, the paper's "
        "MR-KP baseline) on the TA-accumulated frame",
        embeddedWeights().data != nullptr);
    t.create = factoryOf<MrkpFilter>();
    return t;
}

} // namespace afn::mrkp
