// SPDX-License-Identifier: Apache-2.0
// Fuzz target: frame ranges, frame-name patterns and "--aov" overrides (afn/io.hpp). Besides "no
// crash and only IoError", it checks what a sequence relies on: ranges stay within their bounds,
// a name without a pattern expands to itself, and different frames never expand to the same name
// (two frames written to one file would silently overwrite each other).
#include <afn/io.hpp>

#include <fuzzer/FuzzedDataProvider.h>

#include <cstdio>
#include <cstdlib>
#include <set>

namespace {

void check(bool ok, const char* what)
{
    if (!ok) {
        std::fprintf(stderr, "fuzz_frame_pattern: property violated: %s\n", what);
        std::abort();
    }
}

void fuzzRange(const std::string& text)
{
    try {
        const std::vector<int> frames = afn::io::parseFrameRange(text);
        check(!frames.empty() && frames.size() <= 1000000, "a parsed range has 1..1e6 frames");
        for (int f : frames)
            check(f >= -1000000000 && f <= 1000000000, "parsed frames stay within +-1e9");
    } catch (const afn::io::IoError&) {
    }
}

void fuzzPattern(const std::string& pattern, int a, int b)
{
    const bool has = afn::io::hasFramePattern(pattern);
    const std::string ea = afn::io::expandFramePattern(pattern, a);
    const std::string eb = afn::io::expandFramePattern(pattern, b);
    if (!has)
        check(ea == pattern, "a name without a pattern expands to itself");
    else if (a != b)
        check(ea != eb, "different frames expand to different names");
    try {
        const std::vector<std::string> paths
            = afn::io::expandSequence(pattern, { a, b }, /*mustExist=*/false);
        check(has && paths.size() == 2 && paths[0] == ea && paths[1] == eb,
            "expandSequence agrees with expandFramePattern");
    } catch (const afn::io::IoError&) {
        check(!has, "expandSequence fails only without a pattern");
    }
}

void fuzzOverride(const std::string& text)
{
    afn::io::MappingOverrides overrides;
    try {
        afn::io::parseOverride(text, overrides);
        const std::size_t lights = overrides.lights ? 1 : 0;
        check(overrides.channels.size() + overrides.tags.size() + lights == 1,
            "an accepted override sets exactly one role, tag or the light passes");
        if (overrides.lights)
            for (const std::string& item : *overrides.lights)
                check(!item.empty() && item.front() != '*' && item.back() != '*',
                    "an accepted light pass names a layer (and a factor after '*')");
    } catch (const afn::io::IoError&) {
    }
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
    FuzzedDataProvider in(data, size);
    switch (in.ConsumeIntegralInRange<int>(0, 2)) {
    case 0:
        fuzzRange(in.ConsumeRemainingBytesAsString());
        break;
    case 1: {
        const int a = in.ConsumeIntegralInRange<int>(-1000000000, 1000000000);
        const int b = in.ConsumeIntegralInRange<int>(-1000000000, 1000000000);
        fuzzPattern(in.ConsumeRemainingBytesAsString(), a, b);
        break;
    }
    default:
        fuzzOverride(in.ConsumeRemainingBytesAsString());
    }
    return 0;
}
