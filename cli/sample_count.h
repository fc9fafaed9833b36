// SPDX-License-Identifier: Apache-2.0
// The sample count afntool gives a method with an "spp" parameter (AFN_PARAM_SPP: the afn method
// picks its model by it, aux=auto trusts the auxiliary buffers from AFN_AUX_TRUSTED_SPP): the
// user's ":spp=N" wins, else the count the file's header records, else 0 (unknown).
#pragma once

#include <afn/afn.h>

#include <map>
#include <optional>
#include <string>

namespace afntool {

/// The value to set for "spp", or nullopt when nothing is to be set (the method has no such
/// parameter, or the user's modifier sets it).
inline std::optional<int> sampleCountParam(bool methodHasSpp,
    const std::map<std::string, std::string>& userParams, std::optional<int> fileSamples)
{
    if (!methodHasSpp || userParams.count(AFN_PARAM_SPP))
        return std::nullopt;
    return fileSamples.value_or(0);
}

} // namespace afntool
