// SPDX-License-Identifier: Apache-2.0
// Atomic image writing: a temporary file beside the target (same extension, so OpenImageIO picks
// the same format), then rename. Nothing is left behind on failure.
#include "oiio_util.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <filesystem>
#include <unistd.h>

namespace afn::io {
namespace {

namespace fs = std::filesystem;

/// Removes the temporary file unless released.
class TempFile {
public:
    explicit TempFile(fs::path p)
        : m_path(std::move(p))
    {
    }
    ~TempFile()
    {
        if (!m_path.empty()) {
            std::error_code ec;
            fs::remove(m_path, ec);
        }
    }
    TempFile(const TempFile&) = delete;
    TempFile& operator=(const TempFile&) = delete;
    const fs::path& path() const { return m_path; }
    void release() { m_path.clear(); }

private:
    fs::path m_path;
};

fs::path tempPathFor(const fs::path& target)
{
    static std::atomic<unsigned> counter { 0 };
    const std::string name = "." + target.stem().string() + ".afn-tmp-" + std::to_string(::getpid())
        + "-" + std::to_string(counter++) + target.extension().string();
    return target.parent_path() / name;
}

/// OpenImageIO's messages name the file it was given, the temporary one: report the user's path
/// instead, so that no ".<name>.afn-tmp-<pid>-<n>" name ever reaches the user.
std::string userMessage(std::string message, const fs::path& tmp, const std::string& path)
{
    const std::pair<std::string, std::string> swaps[] = { { tmp.string(), path },
        { tmp.filename().string(), fs::path(path).filename().string() } };
    for (const auto& [from, to] : swaps)
        for (std::size_t at = message.find(from); !from.empty() && at != std::string::npos;
             at = message.find(from, at + to.size()))
            message.replace(at, from.size(), to);
    return message;
}

OIIO::TypeDesc typeFromName(const std::string& t)
{
    static const std::pair<const char*, OIIO::TypeDesc> kTypes[] = { { "uint8", OIIO::TypeUInt8 },
        { "uint16", OIIO::TypeUInt16 }, { "uint", OIIO::TypeUInt }, { "half", OIIO::TypeHalf },
        { "float", OIIO::TypeFloat } };
    for (const auto& [name, type] : kTypes)
        if (t == name)
            return type;
    return OIIO::TypeUnknown;
}

/// Largest finite half value.
constexpr float kHalfMax = 65504.0f;

/// Values as each channel's type can hold them: finite values beyond the half range clamped to
/// +-kHalfMax in half channels (they would otherwise become +-Inf; NaN and Inf are kept), [0, 1]
/// in integer channels (NaN -> 0) before quantising.
void clampForTypes(std::vector<float>& px, int nch, const std::vector<std::string>& types)
{
    enum class Kind { Half, Integer, Other };
    std::vector<Kind> kind(static_cast<std::size_t>(nch), Kind::Other);
    for (int c = 0; c < nch; ++c)
        kind[c] = types[c] == "half"                      ? Kind::Half
            : types[c] == "uint8" || types[c] == "uint16" ? Kind::Integer
                                                          : Kind::Other;
    for (std::size_t i = 0; i < px.size(); ++i) {
        float& v = px[i];
        const Kind k = kind[i % nch];
        if (k == Kind::Half && std::isfinite(v))
            v = std::clamp(v, -kHalfMax, kHalfMax);
        else if (k == Kind::Integer)
            v = v > 0.0f ? std::min(v, 1.0f) : 0.0f;
    }
}

/// The pixels of the display window: data inside it copied, the rest 0 (for formats that store
/// no windows; oiiotool's autocrop).
std::vector<float> toDisplayWindow(
    const float* pixels, const Box& data, const Box& display, int nch)
{
    std::vector<float> out(static_cast<std::size_t>(display.width) * display.height * nch, 0.0f);
    const int x0 = std::max(data.x, display.x),
              x1 = std::min(data.x + data.width, display.x + display.width);
    const int y0 = std::max(data.y, display.y),
              y1 = std::min(data.y + data.height, display.y + display.height);
    for (int y = y0; y < y1 && x0 < x1; ++y)
        std::copy_n(
            pixels + ((static_cast<std::size_t>(y - data.y) * data.width) + (x0 - data.x)) * nch,
            static_cast<std::size_t>(x1 - x0) * nch,
            out.data()
                + ((static_cast<std::size_t>(y - display.y) * display.width) + (x0 - display.x))
                    * nch);
    return out;
}

bool sameBox(const Box& a, const Box& b)
{
    return a.x == b.x && a.y == b.y && a.width == b.width && a.height == b.height;
}

void checkArguments(const std::string& path, int width, int height,
    const std::vector<std::string>& channels, const float* pixels, const WriteOptions& options,
    const std::vector<std::string>& types)
{
    if (width <= 0 || height <= 0)
        throw IoError("image size must be positive", path);
    if (channels.empty() || !pixels)
        throw IoError("no channels to write", path);
    if (!types.empty() && types.size() != channels.size())
        throw IoError("one type per channel expected", path);
    if (options.dataWindow
        && (options.dataWindow->width != width || options.dataWindow->height != height))
        throw IoError("data window size does not match the image size", path);
    if (options.displayWindow
        && (options.displayWindow->width <= 0 || options.displayWindow->height <= 0))
        throw IoError("display window size must be positive", path);
    for (const std::string& in : options.inputs)
        if (samePath(path, in))
            throw IoError("refusing to overwrite an input file", path);
    const fs::path target(path);
    const fs::path dir = target.parent_path().empty() ? fs::path(".") : target.parent_path();
    std::error_code ec;
    if (!fs::is_directory(dir, ec))
        throw IoError("output directory does not exist: " + dir.string(), path);
    if (::access(dir.c_str(), W_OK) != 0)
        throw IoError("output directory is not writable: " + dir.string(), path);
    if (fs::is_directory(target, ec))
        throw IoError("output path is a directory", path);
}

} // namespace

bool samePath(const std::string& a, const std::string& b)
{
    std::error_code ec;
    if (fs::exists(a, ec) && fs::exists(b, ec)) {
        const bool eq = fs::equivalent(a, b, ec);
        if (!ec)
            return eq;
    }
    const fs::path ca = fs::weakly_canonical(a, ec);
    if (ec)
        return fs::path(a).lexically_normal() == fs::path(b).lexically_normal();
    const fs::path cb = fs::weakly_canonical(b, ec);
    if (ec)
        return fs::path(a).lexically_normal() == fs::path(b).lexically_normal();
    return ca == cb;
}

void writeImageAtomic(const std::string& path, int width, int height,
    const std::vector<std::string>& channels, const float* pixels, const WriteOptions& options,
    const std::vector<std::string>& types)
{
    checkArguments(path, width, height, channels, pixels, options, types);
    const OutputFormat format = outputFormat(path);
    const int nch = static_cast<int>(channels.size());
    std::string dataType = options.dataType;
    if (dataType.empty())
        dataType = format.storedType(format.name == "openexr" ? "half" : "uint8");
    detail::checkWritable(format, dataType, types, options.compression, path);
    const std::vector<std::string> chTypes
        = types.empty() ? std::vector<std::string>(channels.size(), dataType) : types;

    // Windows: kept where the format stores them, else the display window is written.
    Box data = options.dataWindow.value_or(Box { 0, 0, width, height });
    const Box display = options.displayWindow.value_or(data);
    std::vector<float> values;
    if (!format.windows && !sameBox(data, display)) {
        values = toDisplayWindow(pixels, data, display, nch);
        data = display;
    } else {
        values.assign(pixels, pixels + static_cast<std::size_t>(width) * height * nch);
    }
    clampForTypes(values, nch, chTypes);

    TempFile tmp(tempPathFor(path));
    auto out = OIIO::ImageOutput::create(tmp.path().string());
    if (!out)
        throw IoError(userMessage("no writer for this file type: " + detail::inputError(nullptr),
                          tmp.path(), path),
            path);
    OIIO::ImageSpec spec(data.width, data.height, nch, typeFromName(chTypes[0]));
    if (std::any_of(chTypes.begin(), chTypes.end(), [&](const auto& t) { return t != chTypes[0]; }))
        for (const std::string& t : chTypes)
            spec.channelformats.push_back(typeFromName(t));
    if (format.windows) {
        spec.x = data.x;
        spec.y = data.y;
        spec.full_x = display.x;
        spec.full_y = display.y;
        spec.full_width = display.width;
        spec.full_height = display.height;
    }
    spec.channelnames = channels;
    spec.alpha_channel = -1;
    for (int c = 0; c < nch; ++c)
        if (channels[c] == "A")
            spec.alpha_channel = c;
    detail::applyMetadata(spec, options.metadata);
    for (const auto& [k, v] : options.attributes)
        if (k != "compression")
            spec.attribute(k, v);
    if (format.name == "openexr")
        spec.attribute("compression", options.compression.empty() ? "zip" : options.compression);
    else if (!options.compression.empty())
        spec.attribute("compression", options.compression);
    const float* stored = values.data();

    if (!out->open(tmp.path().string(), spec))
        throw IoError(userMessage("cannot write: " + out->geterror(), tmp.path(), path), path);
    if (!out->write_image(OIIO::TypeDesc::FLOAT, stored)) {
        const std::string err = out->geterror();
        out->close();
        throw IoError(userMessage("cannot write pixels: " + err, tmp.path(), path), path);
    }
    if (!out->close())
        throw IoError(
            userMessage("cannot finish writing: " + out->geterror(), tmp.path(), path), path);
    out.reset();
    std::error_code ec;
    fs::rename(tmp.path(), path, ec);
    if (ec)
        throw IoError("cannot move the finished file into place: " + ec.message(), path);
    tmp.release();
}

} // namespace afn::io
