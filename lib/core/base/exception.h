// SPDX-License-Identifier: Apache-2.0
// The core's one exception type: an error code plus a message. The API layer turns it into the
// device's error state; it never crosses the C boundary.
#pragma once

#include "afn/afn.h"

#include <stdexcept>
#include <string>

namespace afn {

class Exception : public std::runtime_error {
public:
    Exception(AFNError code, const std::string& message)
        : std::runtime_error(message)
        , m_code(code)
    {
    }
    AFNError code() const { return m_code; }

private:
    AFNError m_code;
};

/// Throw an InvalidArgument error.
[[noreturn]] inline void throwInvalidArgument(const std::string& message)
{
    throw Exception(AFN_ERROR_INVALID_ARGUMENT, message);
}

/// Throw an InvalidOperation error.
[[noreturn]] inline void throwInvalidOperation(const std::string& message)
{
    throw Exception(AFN_ERROR_INVALID_OPERATION, message);
}

} // namespace afn
