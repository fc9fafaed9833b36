// SPDX-License-Identifier: Apache-2.0
// Internal helpers of resolveConfig, exposed for tests: where libafn_color lives and the config
// installed beside it.
#pragma once

#include <string>

namespace afn::color::detail {

/// Absolute or loader-given path of the shared library holding afn_color ("" if unknown).
std::string libraryPath();

/// <libdir>/../share/afn/ocio/config.ocio, or <libdir>/../../share/... for multiarch libdirs,
/// for a library file at `libraryFile`; "" when neither exists as a regular file.
std::string installedConfigBeside(const std::string& libraryFile);

} // namespace afn::color::detail
