// SPDX-License-Identifier: Apache-2.0
#include "methods/afn/weights_source.h"

#include "base/exception.h"
#include "nn/weights.h"

#ifdef AFN_HAS_EMBEDDED_WEIGHTS
extern "C" const unsigned char afnEmbeddedWeights[];
extern "C" const unsigned long long afnEmbeddedWeights_size;
#endif

namespace afn::afnet {

bool loadEmbeddedNetwork(Network& net)
{
#ifdef AFN_HAS_EMBEDDED_WEIGHTS
    net.load(nn::WeightsArchive::parse(afnEmbeddedWeights,
        static_cast<std::size_t>(afnEmbeddedWeights_size), "embedded AFN weights"));
    return true;
#else
    (void)net;
    return false;
#endif
}

Network networkFromData(const void* data, std::size_t size)
{
    Network net;
    net.load(nn::WeightsArchive::parse(data, size, "weights set with afnSetFilterData"));
    return net;
}

void throwNoWeights()
{
    throwInvalidOperation(
        "afn: no weights: this build embeds no trained AFN model; set an .afnw file "
        "with afnSetFilterData(filter, \"weights\", data, size) (afntool: --weights FILE)");
}

} // namespace afn::afnet
