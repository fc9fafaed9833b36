// SPDX-License-Identifier: Apache-2.0
// Fuzz target: reading renderer EXRs with afn_io (afn/io.hpp): header inspection, role mapping
// (channel names, layers, multi-part files, data/display windows, channel types) with and
// without "--aov" overrides, decoding every mapped role (and every channel), statistics, and a
// round trip of the colour through the atomic half-float writer.
//
// The input is the file's bytes (the seeds are real EXRs); one middle byte also picks the read
// options. Properties: only afn::io::IoError escapes, decoded images have the sizes their
// headers say, and finite colour stays finite when written as half.
//
// Harness limits (documented in docs/reliability.md): only the OpenEXR reader is tried
// (OpenImageIO's try_all_readers is off), and files whose parts would decode to more than 2^20
// values are inspected and mapped but not decoded (the fuzzer's memory limit).
#include <afn/io.hpp>

#include <OpenImageIO/imageio.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>
#include <unistd.h>

namespace {

constexpr const char* kTarget = "fuzz_exr_reader";
std::string g_input, g_output;

void check(bool ok, const std::string& what)
{
    if (!ok) {
        std::fprintf(stderr, "%s: property violated: %s\n", kTarget, what.c_str());
        std::abort();
    }
}

std::string scratchDir()
{
    if (::access("/dev/shm", W_OK) == 0)
        return "/dev/shm";
    const char* t = std::getenv("TMPDIR");
    return t && *t ? t : "/tmp";
}

afn::io::ReadOptions readOptions(const uint8_t* data, size_t size)
{
    static const char* const kOverrides[] = { nullptr, "albedo=diffuse", "normal.space=camera",
        "depth=Z", "color=R,G,B", "motion=vel.X,vel.Y", "variance=var", "albedo=A.R,A.G,A.B" };
    const unsigned flags = size ? data[size / 2] : 0u;
    afn::io::ReadOptions ro;
    ro.keepAll = flags & 1u;
    ro.required = {};
    if (const char* o = kOverrides[(flags >> 1) & 7u])
        afn::io::parseOverride(o, ro.overrides);
    return ro;
}

bool decodable(const afn::io::FileInfo& info)
{
    for (const afn::io::SubimageInfo& s : info.subimages) {
        const double values = static_cast<double>(s.dataWindow.width)
            * static_cast<double>(s.dataWindow.height) * static_cast<double>(s.channels.size());
        if (s.dataWindow.width <= 0 || s.dataWindow.height <= 0 || values > (1 << 20))
            return false;
    }
    return true;
}

void checkFrame(const afn::io::FrameImages& frame)
{
    for (const auto& [role, img] : frame.roles) {
        check(img.width > 0 && img.height > 0, "a decoded role has an empty size");
        check(img.components == afn::io::roleComponents(role)
                || (role == afn::io::Role::Variance && img.components == 1),
            std::string("role ") + afn::io::roleName(role) + " has the wrong component count");
        check(
            img.pixels.size() == static_cast<std::size_t>(img.width) * img.height * img.components,
            "a role's pixel count does not match its size");
        const afn::io::RoleStats st = afn::io::computeStats(img);
        check(st.count == static_cast<long long>(img.pixels.size()), "statistics count");
    }
    if (frame.all) {
        const afn::io::LayeredImage& all = *frame.all;
        check(all.types.size() == all.channels.size(), "one type per kept channel");
        check(all.pixels.size()
                == static_cast<std::size_t>(all.width) * all.height * all.channels.size(),
            "kept channels' pixel count");
    }
}

/// Write the colour as half and read it back: finite values stay finite.
void roundTrip(const afn::io::RoleImage& color)
{
    if (static_cast<long long>(color.width) * color.height > 4096)
        return;
    bool finite = true;
    for (float v : color.pixels)
        finite = finite && std::isfinite(v);
    const std::vector<std::string> names = { "R", "G", "B" };
    afn::io::WriteOptions wo;
    wo.dataType = "half";
    afn::io::writeImageAtomic(g_output, color.width, color.height,
        std::vector<std::string>(names.begin(), names.begin() + color.components),
        color.pixels.data(), wo);
    const afn::io::FrameImages back = afn::io::readFrame(g_output);
    const afn::io::RoleImage& c = back.roles.at(afn::io::Role::Color);
    check(c.pixels.size() == color.pixels.size(), "round trip changes the size");
    if (finite)
        for (float v : c.pixels)
            check(std::isfinite(v), "finite colour became non-finite when written as half");
}

} // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***)
{
    OIIO::attribute("threads", 1);
    OIIO::attribute("exr_threads", 1);
    OIIO::attribute("try_all_readers", 0);
    const std::string dir = scratchDir();
    const std::string pid = std::to_string(::getpid());
    g_input = dir + "/afn-fuzz-exr-" + pid + ".exr";
    g_output = dir + "/afn-fuzz-exr-" + pid + "-out.exr";
    std::atexit([] {
        std::remove(g_input.c_str());
        std::remove(g_output.c_str());
    });
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
    {
        std::ofstream f(g_input, std::ios::binary | std::ios::trunc);
        f.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
    }
    const afn::io::ReadOptions ro = readOptions(data, size);
    afn::io::FileInfo info;
    try {
        info = afn::io::inspect(g_input);
    } catch (const afn::io::IoError&) {
        return 0;
    }
    check(!info.subimages.empty(), "inspect returned no subimage");
    for (const afn::io::SubimageInfo& s : info.subimages)
        check(s.types.size() == s.channels.size(), "one type per channel");
    // An --aov override naming channels the file lacks is an error (IoError), as for afntool.
    afn::io::RoleMapping mapping;
    try {
        mapping = afn::io::mapRoles(info, ro.overrides);
    } catch (const afn::io::IoError&) {
        return 0;
    }
    for (const afn::io::RoleChannels& rc : mapping.roles) {
        check(rc.subimage >= 0 && rc.subimage < static_cast<int>(info.subimages.size()),
            "a role in a subimage that does not exist");
        check(rc.indices.size() == rc.channels.size() && !rc.indices.empty(),
            "a role's channel list");
        for (int i : rc.indices)
            check(i >= 0 && i < static_cast<int>(info.subimages[rc.subimage].channels.size()),
                "a role's channel index is out of range");
    }
    if (!decodable(info))
        return 0;
    try {
        const afn::io::FrameImages frame = afn::io::readFrame(g_input, ro);
        checkFrame(frame);
        auto color = frame.roles.find(afn::io::Role::Color);
        if (color != frame.roles.end())
            roundTrip(color->second);
    } catch (const afn::io::IoError&) {
    }
    return 0;
}
