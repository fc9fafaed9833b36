// SPDX-License-Identifier: Apache-2.0
// Config resolution order (explicit > $OCIO > afn default) and config loading errors.
#include "afn/color.hpp"
#include "config_paths.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>

using afn::color::ColorError;
using afn::color::ColorManager;
using afn::color::resolveConfig;

namespace {

const std::string kDefault = AFN_SOURCE_DIR "/ocio/config.ocio";

// Restores $OCIO (as the harness set it) when a test ends.
class ColorConfig : public ::testing::Test {
protected:
    void SetUp() override
    {
        const char* v = std::getenv("OCIO");
        m_had = v != nullptr;
        m_saved = v ? v : "";
    }
    void TearDown() override
    {
        if (m_had)
            ::setenv("OCIO", m_saved.c_str(), 1);
        else
            ::unsetenv("OCIO");
    }
    std::string writeFile(const std::string& name, const std::string& text)
    {
        const std::string path = ::testing::TempDir() + "afn_color_" + name;
        std::ofstream(path) << text;
        return path;
    }

private:
    bool m_had = false;
    std::string m_saved;
};

std::string errorOf(const std::string& explicitPath)
{
    try {
        ColorManager cm(explicitPath);
    } catch (const ColorError& e) {
        return e.what();
    }
    return "";
}

} // namespace

TEST_F(ColorConfig, ResolutionOrder)
{
    ::unsetenv("OCIO");
    EXPECT_EQ(resolveConfig().path, kDefault);
    EXPECT_EQ(resolveConfig().reason, "afn default");
    ::setenv("OCIO", "", 1); // empty counts as unset
    EXPECT_EQ(resolveConfig().path, kDefault);
    ::setenv("OCIO", "/env/config.ocio", 1);
    EXPECT_EQ(resolveConfig().path, "/env/config.ocio");
    EXPECT_EQ(resolveConfig().reason, "$OCIO");
    EXPECT_EQ(resolveConfig("/cli/config.ocio").path, "/cli/config.ocio");
    EXPECT_EQ(resolveConfig("/cli/config.ocio").reason, "--colorconfig");
    ::unsetenv("OCIO");
    EXPECT_EQ(resolveConfig("/cli/config.ocio").reason, "--colorconfig");
}

TEST_F(ColorConfig, LoadsFromOcioVariable)
{
    std::ifstream in(kDefault);
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const std::string copy = writeFile("env.ocio", text);
    ::setenv("OCIO", copy.c_str(), 1);
    ColorManager cm;
    EXPECT_EQ(cm.config().path, copy);
    EXPECT_EQ(cm.config().reason, "$OCIO");
    EXPECT_EQ(cm.workingSpace(), "Linear Rec.709");
    // The explicit path still wins over $OCIO.
    EXPECT_EQ(ColorManager(kDefault).config().reason, "--colorconfig");
}

TEST_F(ColorConfig, MissingConfigNamesPathAndSource)
{
    std::string msg = errorOf("/no/such/dir/afn.ocio");
    EXPECT_NE(msg.find("/no/such/dir/afn.ocio"), std::string::npos) << msg;
    EXPECT_NE(msg.find("not found"), std::string::npos) << msg;
    EXPECT_NE(msg.find("--colorconfig"), std::string::npos) << msg;

    ::setenv("OCIO", "/no/such/env.ocio", 1);
    msg = errorOf("");
    EXPECT_NE(msg.find("/no/such/env.ocio"), std::string::npos) << msg;
    EXPECT_NE(msg.find("$OCIO"), std::string::npos) << msg;

    msg = errorOf(::testing::TempDir()); // a directory, not a file
    EXPECT_NE(msg.find("not a regular file"), std::string::npos) << msg;
}

TEST_F(ColorConfig, InvalidConfigNamesPathAndReason)
{
    const std::string bad = writeFile("bad.ocio", "ocio_profile_version: 2.1\nroles: [oops\n");
    std::string msg = errorOf(bad);
    EXPECT_NE(msg.find(bad), std::string::npos) << msg;
    EXPECT_NE(msg.find("invalid colour config"), std::string::npos) << msg;

    // Well-formed YAML whose role points at a colour space that does not exist.
    const std::string dangling = writeFile("dangling.ocio",
        "ocio_profile_version: 2.1\n"
        "roles:\n  scene_linear: Nowhere\n"
        "displays:\n  sRGB:\n"
        "    - !<View> {name: Raw, colorspace: Raw}\n"
        "colorspaces:\n"
        "  - !<ColorSpace> {name: Raw, isdata: true}\n");
    msg = errorOf(dangling);
    EXPECT_NE(msg.find(dangling), std::string::npos) << msg;
    EXPECT_FALSE(msg.empty());
}

TEST(ColorConfigInstall, FindsConfigBesideTheLibrary)
{
    namespace fs = std::filesystem;
    using afn::color::detail::installedConfigBeside;
    // This test links the colour code statically, so the file holding it is the test program.
    const std::string self = afn::color::detail::libraryPath();
    ASSERT_FALSE(self.empty());
    EXPECT_TRUE(fs::equivalent(self, fs::read_symlink("/proc/self/exe"))) << self;

    const fs::path prefix = fs::path(::testing::TempDir()) / "afn_color_prefix";
    fs::remove_all(prefix);
    fs::create_directories(prefix / "lib" / "x86_64-linux-gnu");
    const std::string lib = (prefix / "lib" / "libafn_color.so.0").string();
    const std::string multiarch
        = (prefix / "lib" / "x86_64-linux-gnu" / "libafn_color.so").string();
    EXPECT_EQ(installedConfigBeside(lib), ""); // nothing installed yet

    fs::create_directories(prefix / "share" / "afn" / "ocio");
    std::ofstream(prefix / "share" / "afn" / "ocio" / "config.ocio") << "x";
    const std::string found = installedConfigBeside(lib);
    ASSERT_FALSE(found.empty());
    EXPECT_TRUE(fs::equivalent(found, prefix / "share" / "afn" / "ocio" / "config.ocio"));
    const std::string foundMulti = installedConfigBeside(multiarch);
    ASSERT_FALSE(foundMulti.empty());
    EXPECT_TRUE(fs::equivalent(foundMulti, prefix / "share" / "afn" / "ocio" / "config.ocio"));
    EXPECT_EQ(installedConfigBeside("no-slash.so"), "");
    fs::remove_all(prefix);
}
