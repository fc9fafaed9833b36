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

OIIO::TypeDesc typeFromName(const std::string& t, const std::string& path)
{
    if (t == "half")
        return OIIO::TypeDesc::HALF;
    if (t == "float")
        return OIIO::TypeDesc::FLOAT;
    throw IoError("unknown data type '" + t + "' (half or float)", path);
}

/// Largest finite half value.
constexpr float kHalfMax = 65504.0f;

/// Finite values beyond the half range would be written as +-Inf: clamp them to +-kHalfMax in the
/// channels stored as half (NaN and Inf are kept as they are). Returns `pixels` untouched when no
/// channel is half, else the clamped copy in `storage`.
const float* clampHalfChannels(const float* pixels, std::size_t nvalues, int nch,
    const std::string& dataType, const std::vector<std::string>& types, std::vector<float>& storage)
{
    std::vector<bool> half(static_cast<std::size_t>(nch));
    bool any = false;
    for (int c = 0; c < nch; ++c) {
        half[c] = (types.empty() ? dataType : types[c]) == "half";
        any = any || half[c];
    }
    if (!any)
        return pixels;
    storage.assign(pixels, pixels + nvalues);
    for (std::size_t i = 0; i < nvalues; ++i)
        if (half[i % nch] && std::isfinite(storage[i]))
            storage[i] = std::clamp(storage[i], -kHalfMax, kHalfMax);
    return storage.data();
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
    TempFile tmp(tempPathFor(path));
    auto out = OIIO::ImageOutput::create(tmp.path().string());
    if (!out)
        throw IoError(userMessage("no writer for this file type: " + detail::inputError(nullptr),
                          tmp.path(), path),
            path);
    const std::string format = out->format_name();
    const bool exr = format == "openexr";
    const bool floatOnly = format == "hdr" || format == "pfm";
    const int nch = static_cast<int>(channels.size());
    const std::size_t nvalues = static_cast<std::size_t>(width) * height * nch;

    OIIO::ImageSpec spec(width, height, nch, OIIO::TypeDesc::UINT8);
    std::vector<float> clamped;
    const float* data = pixels;
    if (exr) {
        spec.set_format(typeFromName(options.dataType, path));
        if (!types.empty()) {
            for (const std::string& t : types)
                spec.channelformats.push_back(typeFromName(t, path));
            if (std::all_of(
                    types.begin(), types.end(), [&](const auto& t) { return t == types[0]; })) {
                spec.set_format(spec.channelformats[0]);
                spec.channelformats.clear();
            }
        }
        spec.attribute("compression", options.compression.empty() ? "zip" : options.compression);
        data = clampHalfChannels(pixels, nvalues, nch, options.dataType, types, clamped);
    } else if (floatOnly) {
        spec.set_format(OIIO::TypeDesc::FLOAT);
    } else {
        // 8-bit outputs (PNG, TIFF, JPEG, ...): clamp to [0, 1] (NaN -> 0) before quantising.
        clamped.assign(pixels, pixels + nvalues);
        for (float& v : clamped)
            v = v > 0.0f ? std::min(v, 1.0f) : 0.0f;
        data = clamped.data();
    }
    spec.channelnames = channels;
    spec.alpha_channel = -1;
    for (int c = 0; c < nch; ++c)
        if (channels[c] == "A")
            spec.alpha_channel = c;
    for (const auto& [k, v] : options.attributes)
        if (k != "compression")
            spec.attribute(k, v);

    if (!out->open(tmp.path().string(), spec))
        throw IoError(userMessage("cannot write: " + out->geterror(), tmp.path(), path), path);
    if (!out->write_image(OIIO::TypeDesc::FLOAT, data)) {
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
