// SPDX-License-Identifier: Apache-2.0
// Choosing the OpenColorIO config: explicit path, else $OCIO, else the project's own config.
#include "afn/color.hpp"
#include "config_paths.h"

#include <dlfcn.h>
#include <sys/stat.h>

#include <cstdlib>
#include <string>

namespace afn::color {
namespace {

bool isRegularFile(const std::string& path)
{
    struct stat st { };
    return !path.empty() && ::stat(path.c_str(), &st) == 0 && S_ISREG(st.st_mode);
}

} // namespace

namespace detail {

std::string libraryPath()
{
    Dl_info info {};
    if (::dladdr(reinterpret_cast<void*>(&resolveConfig), &info) == 0 || !info.dli_fname)
        return {};
    return info.dli_fname;
}

std::string installedConfigBeside(const std::string& libraryFile)
{
    const auto slash = libraryFile.rfind('/');
    if (slash == std::string::npos)
        return {};
    const std::string dir = libraryFile.substr(0, slash);
    for (const char* up :
        { "/../share/afn/ocio/config.ocio", "/../../share/afn/ocio/config.ocio" }) {
        const std::string candidate = dir + up;
        if (isRegularFile(candidate))
            return candidate;
    }
    return {};
}

} // namespace detail

ConfigChoice resolveConfig(const std::string& explicitPath)
{
    if (!explicitPath.empty())
        return { explicitPath, "--colorconfig" };
    const char* env = std::getenv("OCIO");
    if (env && *env)
        return { env, "$OCIO" };
    // The source-tree config wins when it exists (build tree, tests); then the installed copy found
    // relative to the library; the compiled-in install path is the last resort (it may not exist,
    // in which case loading it reports that).
    if (isRegularFile(AFN_OCIO_SOURCE_CONFIG))
        return { AFN_OCIO_SOURCE_CONFIG, "afn default" };
    const std::string besideLib = detail::installedConfigBeside(detail::libraryPath());
    if (!besideLib.empty())
        return { besideLib, "afn default" };
    return { AFN_OCIO_INSTALL_CONFIG, "afn default" };
}

} // namespace afn::color
