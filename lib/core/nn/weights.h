// SPDX-License-Identifier: Apache-2.0
// Reader of the afn weights archive (.afnw), written by training/afn/weights.py. Layout
// (little-endian): "AFNW", u32 version (1), u32 tensor count, u32 metadata size, metadata
// ("key=value\n" lines), then per tensor: u16 name size, name, u8 dtype (1 = float32), u8 rank
// (1..4), u32 dims[rank], u64 data offset (from the file start), u64 data size; float32 data.
// Every field is bounds-checked and every value must be finite; any inconsistency throws
// "invalid or corrupted weights: ...".
#pragma once

#include <cstddef>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace afn::nn {

/// One named float32 tensor (PyTorch order, row-major).
struct WeightTensor {
    std::vector<std::int64_t> dims;
    std::vector<float> data;
    std::int64_t numel() const { return static_cast<std::int64_t>(data.size()); }
};

/// A parsed archive: tensors by PyTorch state_dict name, plus string metadata.
class WeightsArchive {
public:
    /// Supported format version.
    static constexpr std::uint32_t kVersion = 1;

    /// Parse `size` bytes (copied); throws afn::Exception (InvalidArgument) naming `source`.
    static WeightsArchive parse(const void* data, std::size_t size, const std::string& source);
    /// An archive made in memory (benchmarks, tests); no validation beyond the layers' own.
    static WeightsArchive fromTensors(std::map<std::string, WeightTensor> tensors,
        std::map<std::string, std::string> meta, const std::string& source);

    bool has(const std::string& name) const { return m_tensors.count(name) != 0; }
    /// The tensor `name`; throws "invalid or corrupted weights: missing tensor 'name'".
    const WeightTensor& tensor(const std::string& name) const;
    /// Metadata value or `fallback`.
    std::string meta(const std::string& key, const std::string& fallback = "") const;
    const std::map<std::string, WeightTensor>& tensors() const { return m_tensors; }
    const std::map<std::string, std::string>& metadata() const { return m_meta; }
    const std::string& source() const { return m_source; }

private:
    std::map<std::string, WeightTensor> m_tensors;
    std::map<std::string, std::string> m_meta;
    std::string m_source;
};

} // namespace afn::nn
