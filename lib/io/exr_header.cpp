// SPDX-License-Identifier: Apache-2.0
// A bounds check of an OpenEXR file's headers before OpenEXR reads them: walked as OpenEXR 3.1
// walks them, every length an attribute declares must fit in what is left of the file. OpenEXR 3.1
// allocates and zero-fills a string attribute of the declared size before it notices that the file
// is too short, so a corrupt 2 kB file declaring a 1.8 GB attribute took 30 s and 2 GB of memory to
// reject (found by fuzz_exr_reader; regression inputs tests/fuzz/corpus/fuzz_exr_reader/regress-*).
// It also rejects a channel whose pixel type is none of OpenEXR's three: OpenEXR 3.1 reads it
// without complaint and OpenImageIO 2.4 then aborts the process on an assertion (found by
// fuzz_exr_reader; regress-unknown-pixel-type).
// Files that are not EXRs and everything beyond the attribute sizes are left to OpenImageIO and
// OpenEXR.
#include "io_internal.h"

#include <cstdint>
#include <fstream>
#include <utility>

namespace afn::io::detail {

namespace {

constexpr std::uint32_t kExrMagic = 20000630; // bytes 76 2f 31 01
constexpr std::uint32_t kMultiPartFlag = 0x1000; // version field bit 12
constexpr int kMaxNameLength = 255; // attribute and type names (long-name files)
constexpr int kLastPixelType = 2; // UINT 0, HALF 1, FLOAT 2

std::uint32_t le32(const unsigned char* b)
{
    return static_cast<std::uint32_t>(b[0]) | static_cast<std::uint32_t>(b[1]) << 8
        | static_cast<std::uint32_t>(b[2]) << 16 | static_cast<std::uint32_t>(b[3]) << 24;
}

/// Reads a file's headers front to back, keeping the position and the bytes left.
class HeaderScan {
public:
    HeaderScan(std::ifstream& file, std::int64_t size, const std::string& path)
        : m_file(file)
        , m_size(size)
        , m_path(path)
    {
    }

    /// A NUL-terminated name; "" is the 0 byte that ends a header.
    std::string name(const char* what)
    {
        std::string s;
        for (char c; (c = byte()) != '\0';) {
            if (static_cast<int>(s.size()) >= kMaxNameLength)
                fail(std::string(what) + " longer than 255 bytes");
            s += c;
        }
        return s;
    }

    /// Skip one attribute's value as OpenEXR 3.1 reads it: most types by their fixed size or by
    /// their contents whatever the declared size says (chlist, preview, stringvector), strings and
    /// unknown types by the declared size. Every length must fit in the rest of the file.
    void skipValue(const std::string& attribute, const std::string& type)
    {
        const std::int64_t size = int32();
        if (size < 0)
            fail("attribute '" + attribute + "' (" + type + ") declares " + std::to_string(size)
                + " bytes");
        if (type == "chlist") {
            for (std::string channel; !(channel = name("channel name")).empty();) {
                const std::int64_t pixelType = int32();
                if (pixelType < 0 || pixelType > kLastPixelType)
                    fail("channel '" + channel + "' has pixel type " + std::to_string(pixelType)
                        + " (OpenEXR knows 0 uint, 1 half and 2 float)");
                skip(12, attribute, type); // pLinear, reserved, x and y sampling
            }
        } else if (type == "preview") {
            const std::int64_t w = static_cast<std::uint32_t>(int32());
            const std::int64_t h = static_cast<std::uint32_t>(int32());
            skip(w * h > m_size ? m_size + 1 : 4 * w * h, attribute, type);
        } else if (type == "stringvector") {
            for (std::int64_t read = 0; read < size;) {
                const std::int64_t length = int32();
                if (length < 0)
                    fail("attribute '" + attribute + "' (stringvector) holds a string of "
                        + std::to_string(length) + " bytes");
                skip(length, attribute, type);
                read += 4 + length;
            }
        } else if (const int fixed = fixedSize(type); fixed > 0) {
            skip(fixed, attribute, type);
        } else {
            skip(size, attribute, type);
        }
    }

private:
    /// Bytes a fixed-size attribute type occupies; 0 for the others.
    static int fixedSize(const std::string& type)
    {
        static const std::pair<const char*, int> kSizes[] = { { "box2i", 16 }, { "box2f", 16 },
            { "chromaticities", 32 }, { "compression", 1 }, { "deepImageState", 1 },
            { "double", 8 }, { "envmap", 1 }, { "float", 4 }, { "int", 4 }, { "keycode", 28 },
            { "lineOrder", 1 }, { "m33f", 36 }, { "m33d", 72 }, { "m44f", 64 }, { "m44d", 128 },
            { "rational", 8 }, { "tiledesc", 9 }, { "timecode", 8 }, { "v2i", 8 }, { "v2f", 8 },
            { "v2d", 16 }, { "v3i", 12 }, { "v3f", 12 }, { "v3d", 24 } };
        for (const auto& [name, bytes] : kSizes)
            if (type == name)
                return bytes;
        return 0;
    }

    void skip(std::int64_t bytes, const std::string& attribute, const std::string& type)
    {
        if (bytes > m_size - m_pos)
            fail("attribute '" + attribute + "' (" + type + ") declares " + std::to_string(bytes)
                + " bytes, " + std::to_string(m_size - m_pos) + " are left in the file");
        m_file.seekg(bytes, std::ios::cur);
        m_pos += bytes;
    }

    std::int64_t int32()
    {
        unsigned char b[4];
        for (unsigned char& c : b)
            c = static_cast<unsigned char>(byte());
        return static_cast<std::int32_t>(le32(b));
    }

    char byte()
    {
        char c = 0;
        if (m_pos >= m_size || !m_file.get(c))
            fail("the file ends inside the header");
        ++m_pos;
        return c;
    }

    /// Names in the message come from a corrupt file: bytes outside printable ASCII are shown as
    /// \xNN so the message stays one readable line.
    [[noreturn]] void fail(const std::string& what) const
    {
        std::string shown;
        for (const char c : what) {
            const auto u = static_cast<unsigned char>(c);
            if (u >= 0x20 && u < 0x7f) {
                shown += c;
            } else {
                static const char kHex[] = "0123456789abcdef";
                shown += { '\\', 'x', kHex[u >> 4], kHex[u & 15] };
            }
        }
        throw IoError("corrupt EXR header: " + shown, m_path);
    }

    std::ifstream& m_file;
    std::int64_t m_size;
    std::int64_t m_pos = 8; // after the magic number and the version field
    const std::string& m_path;
};

} // namespace

void checkExrHeader(const std::string& path)
{
    std::ifstream file(path, std::ios::binary);
    if (!file)
        return; // OpenImageIO reports it
    file.seekg(0, std::ios::end);
    const std::int64_t size = file.tellg();
    file.seekg(0);
    unsigned char head[8];
    if (size < 8 || !file.read(reinterpret_cast<char*>(head), sizeof head))
        return;
    if (le32(head) != kExrMagic)
        return;
    const bool multiPart = (le32(head + 4) & kMultiPartFlag) != 0;
    HeaderScan scan(file, size, path);
    for (;;) { // one header per part; a multi-part file ends its list with an empty header
        std::string attribute = scan.name("attribute name");
        if (attribute.empty())
            return;
        for (; !attribute.empty(); attribute = scan.name("attribute name"))
            scan.skipValue(attribute, scan.name("attribute type"));
        if (!multiPart)
            return;
    }
}

} // namespace afn::io::detail
