// SPDX-License-Identifier: Apache-2.0
// The bundle around the binary as hosts read it: Contents/Info.plist with the CFBundle keys, and
// the icon Contents/Resources/<plugin identifier>.png. The plist's well-formedness and the PNG's
// decoding are checked in full by check_bundle.py (ctest plugin_bundle).
#include "ofx_test_host.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

namespace fs = std::filesystem;
using namespace ofxhost;

namespace {

std::string readFile(const fs::path& p)
{
    std::ifstream in(p, std::ios::binary);
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

/// The <string> after <key>name</key> in a plist ("" when missing).
std::string plistString(const std::string& plist, const std::string& key)
{
    const std::string k = "<key>" + key + "</key>";
    size_t at = plist.find(k);
    if (at == std::string::npos)
        return "";
    at = plist.find("<string>", at + k.size());
    const size_t end = plist.find("</string>", at);
    return at == std::string::npos || end == std::string::npos ? ""
                                                               : plist.substr(at + 8, end - at - 8);
}

uint32_t bigEndian(const std::string& s, size_t at)
{
    return uint32_t(uint8_t(s[at])) << 24 | uint32_t(uint8_t(s[at + 1])) << 16
        | uint32_t(uint8_t(s[at + 2])) << 8 | uint32_t(uint8_t(s[at + 3]));
}

} // namespace

TEST(PluginBundle, HasInfoPlistAndIconWhereHostsLookForThem)
{
    Host host;
    std::string error;
    ASSERT_TRUE(host.load(AFN_OFX_BINARY, &error)) << error;
    ASSERT_EQ(host.describe(), kOfxStatOK);
    const OfxPlugin* plugin = host.plugin();
    const fs::path binary = AFN_OFX_BINARY;
    const fs::path contents = binary.parent_path().parent_path();
    EXPECT_EQ(contents.filename(), "Contents");
    EXPECT_EQ(contents.parent_path().extension(), ".bundle");

    const std::string plist = readFile(contents / "Info.plist");
    ASSERT_FALSE(plist.empty()) << contents / "Info.plist";
    EXPECT_EQ(plist.rfind("<?xml", 0), 0u);
    EXPECT_EQ(plistString(plist, "CFBundleExecutable"), binary.filename().string());
    EXPECT_EQ(plistString(plist, "CFBundlePackageType"), "BNDL");
    EXPECT_EQ(plistString(plist, "CFBundleIdentifier"), plugin->pluginIdentifier);
    EXPECT_EQ(plistString(plist, "CFBundleShortVersionString"),
        std::to_string(plugin->pluginVersionMajor) + "."
            + std::to_string(plugin->pluginVersionMinor));

    // Hosts look for Resources/<identifier>.png; the descriptor names it too (kOfxPropIcon).
    const std::string iconName = std::string(plugin->pluginIdentifier) + ".png";
    const OfxPropertySetStruct& d = host.descriptor()->props;
    ASSERT_TRUE(d.has(kOfxPropIcon));
    EXPECT_EQ(d.getString(kOfxPropIcon, 1), iconName);
    const std::string png = readFile(contents / "Resources" / iconName);
    ASSERT_GT(png.size(), 33u) << contents / "Resources" / iconName;
    EXPECT_EQ(png.substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8));
    EXPECT_EQ(png.substr(12, 4), "IHDR");
    EXPECT_EQ(bigEndian(png, 16), 128u); // width
    EXPECT_EQ(bigEndian(png, 20), 128u); // height
    EXPECT_EQ(int(png[25]), 6); // RGBA
    EXPECT_EQ(host.unload(), kOfxStatOK);
}
