// SPDX-License-Identifier: Apache-2.0
// "nbgd": the neural bilateral grid denoiser (Meng et al. 2020), one of the paper's learned
// baselines. Per frame, after the shared stages (aux prefilter, demodulation, BMFR temporal
// accumulation: the same TA-1spp colour afn reads): the 10-channel input (nn/baseline_input.h),
// the guide network and the three bilateral grids (network.h, bilateral_grid.h), then
// remodulation by the albedo. Weights: the archive embedded at build time (weights/nbgd.afnw,
// trained with training/afn/baselines/train.py) or afnSetFilterData(filter, "weights", ...).
// The filter itself is nn/baseline_filter.h, shared with wskpn; this file gives the network.
#include "methods/nbgd/network.h"
#include "nn/baseline_filter.h"

#ifdef AFN_HAS_NBGD_WEIGHTS
extern "C" const unsigned char nbgdEmbeddedWeights[];
extern "C" const unsigned long long nbgdEmbeddedWeights_size;
#endif

namespace afn::nbgd {

namespace {

nn::EmbeddedWeights embeddedWeights()
{
#ifdef AFN_HAS_NBGD_WEIGHTS
    return { nbgdEmbeddedWeights, static_cast<std::size_t>(nbgdEmbeddedWeights_size) };
#else
    return {};
#endif
}

class NbgdFilter final : public nn::BaselineFilter<Network> {
public:
    explicit NbgdFilter(const FilterType& t)
        : BaselineFilter(t, "NBGD", embeddedWeights())
    {
    }
};

} // namespace

FilterType filterType()
{
    FilterType t = nn::baselineFilterType("nbgd",
        "Neural bilateral grid (Meng et al. 2020): three bilateral grids on the "
        "temporal accumulation, guided and blended by a small network",
        embeddedWeights().data != nullptr);
    t.create = factoryOf<NbgdFilter>();
    return t;
}

} // namespace afn::nbgd
