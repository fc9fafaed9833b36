// SPDX-License-Identifier: Apache-2.0
// Helpers for the afn_io tests: a scratch directory and a writer of synthetic EXRs via OIIO.
#pragma once

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <functional>
#include <string>
#include <unistd.h>
#include <vector>

namespace afn_test {

namespace fs = std::filesystem;

/// A fresh directory under the system temp dir, removed at the end of the test.
class ScratchDir {
public:
    ScratchDir()
    {
        static int counter = 0;
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        std::string name = std::string("afn_io_") + (info ? info->name() : "x") + "_"
            + std::to_string(::getpid()) + "_" + std::to_string(counter++);
        m_path = fs::temp_directory_path() / name;
        fs::remove_all(m_path);
        fs::create_directories(m_path);
    }
    ~ScratchDir()
    {
        std::error_code ec;
        fs::permissions(m_path, fs::perms::owner_all, fs::perm_options::add, ec);
        fs::remove_all(m_path, ec);
    }
    std::string file(const std::string& name) const { return (m_path / name).string(); }
    const fs::path& path() const { return m_path; }
    /// Names of the entries in the directory.
    std::vector<std::string> list() const
    {
        std::vector<std::string> out;
        for (const auto& e : fs::directory_iterator(m_path))
            out.push_back(e.path().filename().string());
        return out;
    }

private:
    fs::path m_path;
};

/// One part of a synthetic EXR. value(x, y, c) gives channel c at data-window pixel (x, y).
struct Part {
    std::string name; ///< part name (multi-part only)
    std::vector<std::string> channels;
    std::vector<std::string> types; ///< "half" | "float" per channel (empty = float)
    int width = 4, height = 3, x = 0, y = 0;
    int fullWidth = 0, fullHeight = 0; ///< display window (0 = data window)
    std::function<float(int, int, int)> value
        = [](int x, int y, int c) { return static_cast<float>(100 * c + 10 * y + x); };
    std::vector<std::pair<std::string, std::string>> attributes;
};

inline OIIO::ImageSpec specOf(const Part& p)
{
    OIIO::ImageSpec spec(
        p.width, p.height, static_cast<int>(p.channels.size()), OIIO::TypeDesc::FLOAT);
    spec.x = p.x;
    spec.y = p.y;
    spec.full_x = 0;
    spec.full_y = 0;
    spec.full_width = p.fullWidth ? p.fullWidth : p.width;
    spec.full_height = p.fullHeight ? p.fullHeight : p.height;
    spec.channelnames = p.channels;
    for (std::size_t c = 0; c < p.channels.size() && !p.types.empty(); ++c)
        spec.channelformats.push_back(
            p.types[c] == "half" ? OIIO::TypeDesc::HALF : OIIO::TypeDesc::FLOAT);
    spec.alpha_channel = -1;
    spec.z_channel = -1;
    spec.attribute("compression", "zip");
    if (!p.name.empty())
        spec.attribute("oiio:subimagename", p.name);
    for (const auto& [k, v] : p.attributes)
        spec.attribute(k, v);
    return spec;
}

inline std::vector<float> pixelsOf(const Part& p)
{
    const std::size_t nch = p.channels.size();
    std::vector<float> px(static_cast<std::size_t>(p.width) * p.height * nch);
    for (int y = 0; y < p.height; ++y)
        for (int x = 0; x < p.width; ++x)
            for (std::size_t c = 0; c < nch; ++c)
                px[(static_cast<std::size_t>(y) * p.width + x) * nch + c]
                    = p.value(x, y, static_cast<int>(c));
    return px;
}

/// Write parts as one EXR (multi-part when more than one); fails the test on error.
inline void writeExr(const std::string& path, const std::vector<Part>& parts)
{
    auto out = OIIO::ImageOutput::create(path);
    ASSERT_TRUE(out);
    std::vector<OIIO::ImageSpec> specs;
    for (const Part& p : parts)
        specs.push_back(specOf(p));
    ASSERT_TRUE(out->open(path, static_cast<int>(specs.size()), specs.data())) << out->geterror();
    for (std::size_t i = 0; i < parts.size(); ++i) {
        if (i > 0)
            ASSERT_TRUE(out->open(path, specs[i], OIIO::ImageOutput::AppendSubimage))
                << out->geterror();
        const std::vector<float> px = pixelsOf(parts[i]);
        ASSERT_TRUE(out->write_image(OIIO::TypeDesc::FLOAT, px.data())) << out->geterror();
    }
    ASSERT_TRUE(out->close());
}

/// A Blender 3.4-like channel list for view layer `vl`.
inline std::vector<std::string> blenderChannels(const std::string& vl)
{
    std::vector<std::string> ch;
    auto add = [&](const std::string& pass, const std::string& comps) {
        for (char c : comps)
            ch.push_back(vl + "." + pass + "." + std::string(1, c));
    };
    add("Combined", "RGBA");
    add("Denoising Albedo", "RGB");
    add("Denoising Normal", "XYZ");
    add("Denoising Depth", "Z");
    add("Depth", "Z");
    add("Normal", "XYZ");
    add("Position", "XYZ");
    add("Vector", "XYZW");
    return ch;
}

} // namespace afn_test
