// SPDX-License-Identifier: Apache-2.0
// Editing .afnw weights archives in tests (the file format of training/afn/weights.py,
// little-endian: "AFNW", u32 version, u32 tensor count, u32 metadata size, metadata, then per
// tensor u16 name size, name, u8 dtype, u8 rank, u32 dims[rank], u64 data offset, u64 data size;
// float32 data).
#pragma once

#include <cstdint>
#include <cstring>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

namespace stress {

/// Call fn(name, values, count) for every tensor of the archive, in place.
inline void forEachTensor(std::vector<char>& archive,
    const std::function<void(const std::string&, float*, std::size_t)>& fn)
{
    auto need = [&](std::size_t pos, std::size_t n) {
        if (pos > archive.size() || n > archive.size() - pos)
            throw std::runtime_error("truncated .afnw archive");
    };
    auto u = [&](std::size_t& pos, int bytes) {
        need(pos, static_cast<std::size_t>(bytes));
        std::uint64_t v = 0;
        for (int i = 0; i < bytes; ++i)
            v |= static_cast<std::uint64_t>(static_cast<unsigned char>(archive[pos + i]))
                << (8 * i);
        pos += static_cast<std::size_t>(bytes);
        return v;
    };
    need(0, 4);
    if (std::memcmp(archive.data(), "AFNW", 4) != 0)
        throw std::runtime_error("not an .afnw archive");
    std::size_t pos = 4;
    u(pos, 4); // version
    const std::uint64_t count = u(pos, 4);
    pos += u(pos, 4); // metadata
    for (std::uint64_t t = 0; t < count; ++t) {
        const std::size_t nameSize = u(pos, 2);
        need(pos, nameSize);
        const std::string name(archive.data() + pos, nameSize);
        pos += nameSize;
        u(pos, 1); // dtype (float32)
        const int rank = static_cast<int>(u(pos, 1));
        for (int d = 0; d < rank; ++d)
            u(pos, 4);
        const std::uint64_t offset = u(pos, 8), bytes = u(pos, 8);
        need(offset, bytes);
        std::vector<float> values(bytes / 4);
        std::memcpy(values.data(), archive.data() + offset, values.size() * 4);
        fn(name, values.data(), values.size());
        std::memcpy(archive.data() + offset, values.data(), values.size() * 4);
    }
}

} // namespace stress
