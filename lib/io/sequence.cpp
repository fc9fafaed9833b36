// SPDX-License-Identifier: Apache-2.0
// Frame sequences in oiiotool's conventions: ranges ("1-10x2,20") and name patterns (#, @, %0Nd).
#include "afn/io.hpp"

#include <cctype>
#include <filesystem>

namespace afn::io {
namespace {

/// Parse a signed integer at text[pos]; advances pos. False when there is none.
bool parseInt(const std::string& text, std::size_t& pos, long long& out)
{
    std::size_t p = pos;
    bool neg = false;
    if (p < text.size() && (text[p] == '-' || text[p] == '+'))
        neg = text[p++] == '-';
    const std::size_t digits = p;
    long long v = 0;
    while (p < text.size() && std::isdigit(static_cast<unsigned char>(text[p]))) {
        v = v * 10 + (text[p++] - '0');
        if (v > 1000000000LL)
            return false;
    }
    if (p == digits)
        return false;
    out = neg ? -v : v;
    pos = p;
    return true;
}

/// A "%d" / "%0Nd" at s[pos]: its length and width (0 = none); false if not such a spec.
bool printfSpec(const std::string& s, std::size_t pos, std::size_t& len, int& width)
{
    if (s[pos] != '%')
        return false;
    std::size_t p = pos + 1;
    width = 0;
    // Digits beyond a width of 32 make the spec invalid; stop accumulating so that a long run of
    // digits cannot overflow.
    for (; p < s.size() && std::isdigit(static_cast<unsigned char>(s[p])); ++p)
        if (width <= 32)
            width = width * 10 + (s[p] - '0');
    if (p >= s.size() || s[p] != 'd' || width > 32)
        return false;
    len = p + 1 - pos;
    return true;
}

std::string padded(int frame, int width)
{
    // printf semantics: the width includes the sign ("%04d" of -7 is "-007"), as oiiotool's fmt.
    // Built without a fixed buffer: a long run of '#' or '@' must not truncate the number.
    const long long magnitude = frame < 0 ? -static_cast<long long>(frame) : frame;
    const std::string digits = std::to_string(magnitude);
    std::string out = frame < 0 ? "-" : "";
    const std::size_t used = out.size() + digits.size();
    if (width > 0 && static_cast<std::size_t>(width) > used)
        out.append(static_cast<std::size_t>(width) - used, '0');
    return out + digits;
}

} // namespace

std::vector<int> parseFrameRange(const std::string& text)
{
    std::vector<int> frames;
    if (text.empty())
        throw IoError("empty frame range");
    std::size_t start = 0;
    while (start <= text.size()) {
        std::size_t end = text.find(',', start);
        if (end == std::string::npos)
            end = text.size();
        const std::string item = text.substr(start, end - start);
        std::size_t pos = 0;
        long long a = 0, b = 0, step = 1;
        bool ok = parseInt(item, pos, a);
        b = a;
        if (ok && pos < item.size() && item[pos] == '-') {
            ++pos;
            ok = parseInt(item, pos, b);
            if (ok && pos < item.size() && item[pos] == 'x') {
                ++pos;
                ok = parseInt(item, pos, step) && step > 0;
            }
        }
        if (!ok || pos != item.size())
            throw IoError("bad frame range '" + text + "' (expected e.g. 1-10, 1-10x2, 1,3,5)");
        const long long count = (a <= b ? b - a : a - b) / step + 1;
        if (count + static_cast<long long>(frames.size()) > 1000000)
            throw IoError("frame range '" + text + "' is too long");
        for (long long f = a, i = 0; i < count; ++i, f += (a <= b ? step : -step))
            frames.push_back(static_cast<int>(f));
        start = end + 1;
        if (end == text.size())
            break;
    }
    return frames;
}

bool hasFramePattern(const std::string& pattern)
{
    for (std::size_t i = 0; i < pattern.size(); ++i) {
        std::size_t len = 0;
        int width = 0;
        if (pattern[i] == '#' || pattern[i] == '@' || printfSpec(pattern, i, len, width))
            return true;
    }
    return false;
}

std::string expandFramePattern(const std::string& pattern, int frame)
{
    std::string out;
    for (std::size_t i = 0; i < pattern.size();) {
        const char c = pattern[i];
        std::size_t len = 0;
        int width = 0;
        if (c == '#' || c == '@') {
            std::size_t run = 0;
            while (i + run < pattern.size() && pattern[i + run] == c)
                ++run;
            // oiiotool: '#' is 4 digits and '@' 1 digit each (verified: oiiotool writes x.#.exr
            // as x.0007.exr but x.####.exr with 16 digits). A run of several '#' follows the
            // Nuke/Houdini reading instead (one digit each), as io.hpp documents and the CLI and
            // README use: "shot.####.exr" -> "shot.0007.exr".
            const std::size_t digits = c == '#' && run == 1 ? 4 : run;
            out += padded(frame, static_cast<int>(digits));
            i += run;
        } else if (printfSpec(pattern, i, len, width)) {
            out += padded(frame, width);
            i += len;
        } else {
            out += c;
            ++i;
        }
    }
    return out;
}

std::vector<std::string> expandSequence(
    const std::string& pattern, const std::vector<int>& frames, bool mustExist)
{
    if (!hasFramePattern(pattern))
        throw IoError("no frame pattern (#, @ or %0Nd) in the file name", pattern);
    std::vector<std::string> paths;
    for (int f : frames) {
        std::string p = expandFramePattern(pattern, f);
        std::error_code ec;
        if (mustExist && !std::filesystem::is_regular_file(p, ec))
            throw IoError("missing frame " + std::to_string(f) + " of the sequence", p);
        paths.push_back(std::move(p));
    }
    return paths;
}

} // namespace afn::io
