// SPDX-License-Identifier: Apache-2.0
#include "options.h"

#include "arg_checks.h"
#include "cli_error.h"
#include "near_match.h"

namespace afntool {

std::string splitModifiers(const std::string& arg, std::map<std::string, std::string>& mods)
{
    std::size_t pos = arg.find(':');
    const std::string name = arg.substr(0, pos);
    while (pos != std::string::npos) {
        const std::size_t next = arg.find(':', pos + 1);
        const std::string item
            = arg.substr(pos + 1, next == std::string::npos ? next : next - pos - 1);
        const std::size_t eq = item.find('=');
        if (item.empty() || eq == 0)
            throw CliError("malformed modifier in '" + arg + "' (expected :key=value)");
        if (eq == std::string::npos)
            mods[item] = "1";
        else
            mods[item.substr(0, eq)] = item.substr(eq + 1);
        pos = next;
    }
    return name;
}

namespace {

const char* needValue(int& i, int argc, const char* const* argv, const std::string& flag)
{
    if (i + 1 >= argc)
        throw CliError(flag + " needs an argument");
    return argv[++i];
}

int parseInt(const std::string& text, const std::string& flag)
{
    try {
        std::size_t used = 0;
        const int v = std::stoi(text, &used);
        if (used != text.size())
            throw std::invalid_argument(text);
        return v;
    } catch (const std::exception&) {
        throw CliError(flag + " expects an integer, got '" + text + "'");
    }
}

/// Every flag the parser below accepts (for "did you mean" suggestions).
std::vector<std::string> knownFlags()
{
    return { "--help", "--methods", "--version", "--frames", "--preroll", "--colorconfig",
        "--incolorspace", "--outcolorspace", "--aov", "--threads", "--device", "--weights", "-d",
        "--compression", "--keep-aovs", "--json", "--quiet", "--verbose", "--info", "--denoise",
        "--features", "--preview", "--contact-sheet", "--compare", "--benchmark", "--report" };
}

} // namespace

Options parseCommandLine(int argc, const char* const* argv)
{
    Options o;
    o.usage = argc <= 1; // no arguments: usage, as oiiotool does
    for (int i = 1; i < argc; ++i) {
        const std::string raw = argv[i];
        if (raw.size() < 2 || raw[0] != '-') {
            o.inputs.push_back(raw);
            continue;
        }
        std::map<std::string, std::string> mods;
        const std::string flag = splitModifiers(raw, mods);
        if (flag == "-h" || flag == "--help") {
            o.help = true;
            if (i + 1 < argc && argv[i + 1][0] != '-')
                o.helpTopic = argv[++i]; // --help METHOD

        } else if (flag == "--methods") {
            o.methods = true;
        } else if (flag == "--version") {
            o.version = true;
        } else if (flag == "--frames") {
            o.frames = needValue(i, argc, argv, flag);
        } else if (flag == "--colorconfig") {
            o.colorConfig = needValue(i, argc, argv, flag);
        } else if (flag == "--incolorspace") {
            o.inColorSpace = needValue(i, argc, argv, flag);
        } else if (flag == "--outcolorspace") {
            o.outColorSpace = needValue(i, argc, argv, flag);
        } else if (flag == "--aov") {
            parseAovArgument(needValue(i, argc, argv, flag), o.overrides);
        } else if (flag == "--threads") {
            o.threads = parseInt(needValue(i, argc, argv, flag), flag);
            if (o.threads < 0)
                throw CliError("--threads must be >= 0");
        } else if (flag == "--preroll") {
            o.preroll = parseInt(needValue(i, argc, argv, flag), flag);
            if (o.preroll < 0)
                throw CliError("--preroll must be >= 0, got " + std::to_string(o.preroll));
        } else if (flag == "--device") {
            o.device = needValue(i, argc, argv, flag);
            if (o.device != "cpu" && o.device != "cuda" && o.device != "auto")
                throw CliError("--device expects cpu, cuda or auto, got '" + o.device + "'");
        } else if (flag == "--weights") {
            o.weights = needValue(i, argc, argv, flag);
        } else if (flag == "-d") {
            o.dataType = needValue(i, argc, argv, flag);
            if (o.dataType != "uint8" && o.dataType != "uint16" && o.dataType != "half"
                && o.dataType != "float")
                throw CliError("-d expects uint8, uint16, half or float, got '" + o.dataType + "'");
        } else if (flag == "--compression") {
            o.compression = needValue(i, argc, argv, flag);
        } else if (flag == "--keep-aovs") {
            o.keepAovs = true;
        } else if (flag == "--json") {
            o.json = true;
        } else if (flag == "-q" || flag == "--quiet") {
            o.quiet = true;
        } else if (flag == "-v" || flag == "--verbose") {
            o.verbose = true;
        } else if (flag == "--info") {
            o.actions.push_back({ "info", "", mods });
        } else if (flag == "--denoise") {
            o.actions.push_back({ "denoise", "", mods });
        } else if (flag == "--features") {
            o.actions.push_back({ "features", needValue(i, argc, argv, flag), mods });
        } else if (flag == "--preview") {
            o.actions.push_back({ "preview", needValue(i, argc, argv, flag), mods });
        } else if (flag == "--contact-sheet") {
            o.actions.push_back({ "contact-sheet", needValue(i, argc, argv, flag), mods });
        } else if (flag == "--compare") {
            o.actions.push_back({ "compare", needValue(i, argc, argv, flag), mods });
        } else if (flag == "--benchmark") {
            o.actions.push_back({ "benchmark", "", mods });
        } else if (flag == "--report") {
            o.report = needValue(i, argc, argv, flag);
        } else if (flag == "-o") {
            o.actions.push_back({ "output", needValue(i, argc, argv, flag), mods });
        } else {
            throw CliError("unknown argument '" + raw + "'" + didYouMean(flag, knownFlags())
                + " (see afntool --help)");
        }
    }
    return o;
}

} // namespace afntool
