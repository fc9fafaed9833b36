// SPDX-License-Identifier: Apache-2.0
#include "arg_checks.h"

#include "cli_error.h"
#include "near_match.h"

#include "afn/afn.hpp"

#include <algorithm>

namespace afntool {

namespace {

std::vector<std::string> roleNames()
{
    std::vector<std::string> names;
    for (int r = 0; r < afn::io::kNumRoles; ++r)
        names.push_back(afn::io::roleName(static_cast<afn::io::Role>(r)));
    return names;
}

std::vector<std::string> conventionNames()
{
    std::vector<std::string> names;
    for (const auto& [name, value] : afn::io::SpaceTag {}.parameters())
        names.push_back(name);
    return names;
}

/// Modifiers each action takes (actions absent here check their own or take none).
const std::map<std::string, std::vector<std::string>>& allowedModifiers()
{
    static const std::map<std::string, std::vector<std::string>> table = {
        { "preview", { "display", "view" } },
        { "contact-sheet", { "display", "view", "columns", "tilesize" } },
        { "info", {} },
    };
    return table;
}

} // namespace

void parseAovArgument(const std::string& text, afn::io::MappingOverrides& overrides)
{
    const std::size_t eq = text.find('=');
    std::string key = text.substr(0, eq);
    while (!key.empty() && key.back() == ' ')
        key.pop_back();
    if (eq != std::string::npos && !key.empty()) {
        const bool convention = key.find('.') != std::string::npos;
        if (convention) {
            const std::vector<std::string> names = conventionNames();
            if (std::find(names.begin(), names.end(), key) == names.end())
                throw CliError("--aov: unknown convention '" + key + "'" + didYouMean(key, names)
                    + " (conventions: " + joinNames(names) + ")");
        } else if (!afn::io::roleFromName(key) && key != "lights") {
            std::vector<std::string> roles = roleNames();
            roles.push_back("lights");
            throw CliError("--aov: unknown role '" + key + "'" + didYouMean(key, roles)
                + " (roles: " + joinNames(roles) + ")");
        }
    }
    try {
        afn::io::parseOverride(text, overrides);
    } catch (const afn::io::IoError& e) {
        // afn_io's messages already start with "--aov".
        const std::string what = e.what();
        throw CliError(what.rfind("--aov", 0) == 0 ? what : "--aov: " + what);
    }
}

void checkActionModifiers(const Options& opts)
{
    for (const Action& a : opts.actions) {
        auto it = allowedModifiers().find(a.name);
        if (it == allowedModifiers().end())
            continue;
        const std::vector<std::string>& allowed = it->second;
        for (const auto& [key, value] : a.mods)
            if (std::find(allowed.begin(), allowed.end(), key) == allowed.end())
                throw CliError("--" + a.name + ": unknown modifier '" + key + "'"
                    + didYouMean(key, allowed)
                    + (allowed.empty() ? " (it takes none)"
                                       : " (known: " + joinNames(allowed) + ")"));
    }
}

void checkMethodName(const std::string& flag, const std::string& method)
{
    const std::vector<std::string> methods = afn::filterTypes();
    if (std::find(methods.begin(), methods.end(), method) == methods.end())
        throw CliError(flag + ": unknown method '" + method + "'" + didYouMean(method, methods)
            + " (methods: " + joinNames(methods) + ")");
}

void checkMethodParameters(const std::string& flag, const std::string& method,
    const std::map<std::string, std::string>& params, const std::vector<std::string>& extra)
{
    std::vector<std::string> names;
    for (const AFNParamInfo& p : afn::filterTypeParams(method.c_str()))
        names.push_back(p.name);
    for (const auto& [key, value] : params) {
        if (std::find(names.begin(), names.end(), key) != names.end()
            || std::find(extra.begin(), extra.end(), key) != extra.end())
            continue;
        std::vector<std::string> all = names;
        all.insert(all.end(), extra.begin(), extra.end());
        throw CliError(flag + ": " + method + " has no parameter '" + key + "'"
            + didYouMean(key, all) + " (afntool --help " + method + " lists them)");
    }
}

} // namespace afntool
