// SPDX-License-Identifier: Apache-2.0
// A bounds check of an OpenEXR file's headers before OpenEXR reads them: every attribute's
// declared size must fit in what is left of the file. OpenEXR 3.1 allocates and zero-fills a
// string attribute of the declared size before it notices that the file is too short, so a
// corrupt 2 kB file declaring a 1.8 GB attribute took 30 s and 2 GB of memory to reject (found by
// fuzz_exr_reader; regression inputs tests/fuzz/corpus/fuzz_exr_reader/regress-*). Files that
// are not EXRs and everything beyond the attribute sizes are left to OpenImageIO and OpenEXR.
#include "io_internal.h"

#include <cstdint>
#include <fstream>

namespace afn::io::detail {

namespace {

constexpr std::uint32_t kExrMagic = 20000630; // bytes 76 2f 31 01
constexpr std::uint32_t kMultiPartFlag = 0x1000; // version field bit 12
constexpr int kMaxNameLength = 255; // attribute and type names (long-name files)

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

    /// Skip one attribute's value after reading its declared size.
    void skipValue(const std::string& attribute, const std::string& type)
    {
        unsigned char b[4];
        for (unsigned char& c : b)
            c = static_cast<unsigned char>(byte());
        const std::int64_t size = static_cast<std::int32_t>(le32(b));
        if (size < 0 || size > m_size - m_pos)
            fail("attribute '" + attribute + "' (" + type + ") declares " + std::to_string(size)
                + " bytes, " + std::to_string(m_size - m_pos) + " are left in the file");
        m_file.seekg(size, std::ios::cur);
        m_pos += size;
    }

private:
    char byte()
    {
        char c = 0;
        if (m_pos >= m_size || !m_file.get(c))
            fail("the file ends inside the header");
        ++m_pos;
        return c;
    }

    [[noreturn]] void fail(const std::string& what) const
    {
        throw IoError("corrupt EXR header: " + what, m_path);
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
