// SPDX-License-Identifier: Apache-2.0
// What each output format can store (data types, compressions, windows), so that a request the
// format cannot honour is refused with the valid choices instead of being silently changed.
// The tables follow OpenImageIO 2.4's writers; a format not listed here is written as uint8.
#include "oiio_util.h"

#include <algorithm>

namespace afn::io {
namespace {

struct FormatTable {
    const char* name;
    std::vector<std::string> types;
    std::vector<std::string> compressions;
    bool windows;
};

// clang-format off
const std::vector<FormatTable>& formatTables()
{
    static const std::vector<FormatTable> kTables = {
        { "openexr", { "half", "float", "uint" },
          { "none", "rle", "zips", "zip", "piz", "pxr24", "b44", "b44a", "dwaa", "dwab" }, true },
        // OpenImageIO 2.4 writes half TIFFs as float, so half is not offered.
        { "tiff", { "uint8", "uint16", "float" }, { "none", "lzw", "zip", "packbits" }, false },
        { "png", { "uint8", "uint16" }, { "zip" }, false },
        { "jpeg", { "uint8" }, { "jpeg" }, false },
        { "hdr", { "float" }, {}, false },
        { "pfm", { "float" }, {}, false },
    };
    return kTables;
}
// clang-format on

bool has(const std::vector<std::string>& list, const std::string& s)
{
    return std::find(list.begin(), list.end(), s) != list.end();
}

bool isFloatType(const std::string& t)
{
    return t == "half" || t == "float" || t == "double";
}

} // namespace

std::string OutputFormat::storedType(const std::string& wanted) const
{
    if (has(dataTypes, wanted))
        return wanted;
    if (isFloatType(wanted)) {
        for (const char* t : { "float", "half", "uint8", "uint16" })
            if (has(dataTypes, t))
                return t;
    } else {
        // An integer image in a float format: half holds 8 bits exactly, wider needs float.
        const bool narrow = wanted == "uint8" || wanted == "int8";
        for (const char* t : { narrow ? "half" : "float", narrow ? "float" : "half", "uint16" })
            if (has(dataTypes, t))
                return t;
    }
    return dataTypes.empty() ? wanted : dataTypes.front();
}

bool OutputFormat::acceptsCompression(const std::string& compression) const
{
    return has(compressions, compression.substr(0, compression.find(':')));
}

OutputFormat outputFormat(const std::string& path)
{
    auto out = OIIO::ImageOutput::create(path);
    if (!out)
        throw IoError("no writer for this file type: " + detail::inputError(nullptr), path);
    OutputFormat f;
    f.name = out->format_name();
    for (const FormatTable& t : formatTables())
        if (f.name == t.name) {
            f.dataTypes = t.types;
            f.compressions = t.compressions;
            f.windows = t.windows;
            return f;
        }
    f.dataTypes = { "uint8" };
    return f;
}

namespace detail {

std::string joinChoices(const std::vector<std::string>& list)
{
    std::string out;
    for (const std::string& s : list)
        out += (out.empty() ? "" : ", ") + s;
    return out;
}

void checkWritable(const OutputFormat& format, const std::string& dataType,
    const std::vector<std::string>& types, const std::string& compression, const std::string& path)
{
    auto checkType = [&](const std::string& t) {
        if (!has(format.dataTypes, t))
            throw IoError("data type '" + t + "' cannot be stored in " + format.name
                    + " (valid: " + joinChoices(format.dataTypes) + ")",
                path);
    };
    if (types.empty())
        checkType(dataType);
    for (const std::string& t : types)
        checkType(t);
    if (!compression.empty() && !format.acceptsCompression(compression))
        throw IoError("compression '" + compression + "' is not available for " + format.name
                + (format.compressions.empty()
                        ? " (it has no compression choices)"
                        : " (valid: " + joinChoices(format.compressions) + ")"),
            path);
}

} // namespace detail

} // namespace afn::io
