// SPDX-License-Identifier: Apache-2.0
// Bounds-checked parsing of the .afnw weights archive (format in nn/weights.h).
#include "nn/weights.h"

#include "base/exception.h"

#include <cmath>
#include <cstring>
#include <utility>

namespace afn::nn {

namespace {

class Reader {
public:
    Reader(const unsigned char* p, std::size_t n, const std::string& src)
        : m_p(p)
        , m_n(n)
        , m_src(src)
    {
    }

    [[noreturn]] void fail(const std::string& what) const
    {
        throwInvalidArgument("invalid or corrupted weights (" + m_src + "): " + what);
    }
    void need(std::size_t pos, std::size_t bytes, const char* what) const
    {
        if (pos > m_n || bytes > m_n - pos)
            fail(std::string("truncated ") + what);
    }
    template <typename T> T read(std::size_t& pos, const char* what) const
    {
        need(pos, sizeof(T), what);
        T v = 0;
        // Little-endian on disk; assemble byte by byte so the host order does not matter.
        for (std::size_t i = 0; i < sizeof(T); ++i)
            v = static_cast<T>(v | (static_cast<T>(m_p[pos + i]) << (8 * i)));
        pos += sizeof(T);
        return v;
    }
    std::string bytes(std::size_t& pos, std::size_t n, const char* what) const
    {
        need(pos, n, what);
        std::string s(reinterpret_cast<const char*>(m_p + pos), n);
        pos += n;
        return s;
    }
    std::size_t size() const { return m_n; }
    const unsigned char* data() const { return m_p; }

private:
    const unsigned char* m_p;
    std::size_t m_n;
    const std::string& m_src;
};

} // namespace

WeightsArchive WeightsArchive::parse(const void* data, std::size_t size, const std::string& source)
{
    WeightsArchive a;
    a.m_source = source;
    if (!data)
        throwInvalidArgument("invalid or corrupted weights (" + source + "): no data");
    Reader r(static_cast<const unsigned char*>(data), size, source);
    std::size_t pos = 0;
    if (r.bytes(pos, 4, "header") != "AFNW") {
        if (size >= 7 && std::memcmp(data, "version", 7) == 0)
            r.fail("this is a Git LFS pointer file, not the weights (run git lfs pull)");
        r.fail("bad magic (not an .afnw file)");
    }
    const auto version = r.read<std::uint32_t>(pos, "header");
    if (version != kVersion)
        throwInvalidArgument("unsupported weights format version " + std::to_string(version)
            + " in " + source + " (this build reads version " + std::to_string(kVersion) + ")");
    const auto count = r.read<std::uint32_t>(pos, "header");
    const auto metaSize = r.read<std::uint32_t>(pos, "header");
    const std::string meta = r.bytes(pos, metaSize, "metadata");
    for (std::size_t b = 0; b < meta.size();) {
        std::size_t e = meta.find('\n', b);
        if (e == std::string::npos)
            e = meta.size();
        const std::string line = meta.substr(b, e - b);
        const std::size_t eq = line.find('=');
        if (eq != std::string::npos)
            a.m_meta[line.substr(0, eq)] = line.substr(eq + 1);
        b = e + 1;
    }
    for (std::uint32_t t = 0; t < count; ++t) {
        const auto nameSize = r.read<std::uint16_t>(pos, "tensor table");
        const std::string name = r.bytes(pos, nameSize, "tensor table");
        const auto dtype = r.read<std::uint8_t>(pos, "tensor table");
        const auto rank = r.read<std::uint8_t>(pos, "tensor table");
        if (dtype != 1)
            r.fail("tensor '" + name + "' has unknown dtype " + std::to_string(dtype));
        if (rank < 1 || rank > 4)
            r.fail("tensor '" + name + "' has rank " + std::to_string(rank));
        WeightTensor w;
        std::uint64_t numel = 1;
        for (int d = 0; d < rank; ++d) {
            const auto dim = r.read<std::uint32_t>(pos, "tensor table");
            if (dim > (1u << 28))
                r.fail("tensor '" + name + "' dimension too large");
            numel *= dim;
            if (numel > (std::uint64_t(1) << 30))
                r.fail("tensor '" + name + "' too large");
            w.dims.push_back(dim);
        }
        const auto offset = r.read<std::uint64_t>(pos, "tensor table");
        const auto bytes = r.read<std::uint64_t>(pos, "tensor table");
        if (bytes != numel * 4)
            r.fail("tensor '" + name + "' data size does not match its dims");
        if (offset > size || bytes > size - offset)
            r.fail("tensor '" + name + "' lies outside the file");
        if (a.m_tensors.count(name))
            r.fail("duplicate tensor '" + name + "'");
        w.data.resize(numel);
        std::size_t dpos = static_cast<std::size_t>(offset);
        for (std::uint64_t i = 0; i < numel; ++i) {
            const std::uint32_t bits = r.read<std::uint32_t>(dpos, "tensor data");
            std::memcpy(&w.data[i], &bits, 4);
            if (!std::isfinite(w.data[i]))
                r.fail("tensor '" + name + "' holds a non-finite value at " + std::to_string(i));
        }
        a.m_tensors.emplace(name, std::move(w));
    }
    return a;
}

WeightsArchive WeightsArchive::fromTensors(std::map<std::string, WeightTensor> tensors,
    std::map<std::string, std::string> meta, const std::string& source)
{
    WeightsArchive a;
    a.m_tensors = std::move(tensors);
    a.m_meta = std::move(meta);
    a.m_source = source;
    return a;
}

const WeightTensor& WeightsArchive::tensor(const std::string& name) const
{
    auto it = m_tensors.find(name);
    if (it == m_tensors.end())
        throwInvalidArgument(
            "invalid or corrupted weights (" + m_source + "): missing tensor '" + name + "'");
    return it->second;
}

std::string WeightsArchive::meta(const std::string& key, const std::string& fallback) const
{
    auto it = m_meta.find(key);
    return it == m_meta.end() ? fallback : it->second;
}

} // namespace afn::nn
