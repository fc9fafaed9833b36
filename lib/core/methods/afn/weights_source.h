// SPDX-License-Identifier: Apache-2.0
// Where the afn filters (CPU and CUDA) get their network: the shipped archive embedded at build
// time (cmake/AfnEmbed.cmake, AFN_WEIGHTS_FILE) when the build has one, else none;
// afnSetFilterData(filter, AFN_DATA_WEIGHTS, data, size) overrides at run time. Without weights a
// filter's commit fails with a message: untrained weights never run silently.
#pragma once

#include "methods/afn/network.h"

#include <cstddef>

namespace afn::afnet {

/// Load the weights built into the library into `net`; false (net unchanged) when there are none.
bool loadEmbeddedNetwork(Network& net);

/// A network from an archive given with afnSetFilterData; throws InvalidArgument for invalid or
/// corrupted data.
Network networkFromData(const void* data, std::size_t size);

/// The commit error of an afn filter without weights.
[[noreturn]] void throwNoWeights();

} // namespace afn::afnet
