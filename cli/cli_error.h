// SPDX-License-Identifier: Apache-2.0
// The CLI's error type: printed as "afntool ERROR: <what> (<file>)" with a non-zero exit.
#pragma once

#include <stdexcept>
#include <string>

namespace afntool {

class CliError : public std::runtime_error {
public:
    CliError(const std::string& what, std::string file = {})
        : std::runtime_error(what)
        , m_file(std::move(file))
    {
    }
    const std::string& file() const { return m_file; }

private:
    std::string m_file;
};

} // namespace afntool
