// SPDX-License-Identifier: Apache-2.0
// Small text helpers shared by afntool's actions.
#pragma once

#include <sstream>
#include <string>
#include <vector>

namespace afntool {

/// The non-empty items of `s` separated by `sep` ("a,,b" -> {"a", "b"}).
inline std::vector<std::string> splitList(const std::string& s, char sep)
{
    std::vector<std::string> out;
    std::stringstream ss(s);
    std::string item;
    while (std::getline(ss, item, sep))
        if (!item.empty())
            out.push_back(item);
    return out;
}

} // namespace afntool
