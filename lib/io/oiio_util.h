// SPDX-License-Identifier: Apache-2.0
// OpenImageIO helpers private to afn_io: opening inputs with clear errors, reading specs.
#pragma once

#include "io_internal.h"

#include <OpenImageIO/imageio.h>

#include <memory>

namespace afn::io::detail {

/// Open for reading; IoError naming the file when missing or unreadable.
std::unique_ptr<OIIO::ImageInput> openInput(const std::string& path);

/// Specs of every subimage (parts of multi-part EXRs).
std::vector<OIIO::ImageSpec> readSpecs(OIIO::ImageInput& in, const std::string& path);

/// Name of a subimage ("" when unnamed).
std::string partName(const OIIO::ImageSpec& spec);

/// FileInfo from already-read specs (what inspect() returns).
FileInfo infoFromSpecs(
    const std::string& path, const std::string& format, const std::vector<OIIO::ImageSpec>& specs);

/// The header an output should carry over (header_metadata.cpp): the part's windows, the type of
/// channel `colorChannel`, the compression (EXR) and the attributes worth keeping.
FrameHeader readHeader(const OIIO::ImageSpec& spec, const std::string& format, int colorChannel);

/// Set typed attributes (FrameHeader::attributes) on a spec; unknown types are skipped.
void applyMetadata(OIIO::ImageSpec& spec, const std::vector<Attribute>& attributes);

/// Throw IoError (with the valid choices) when a data type or compression cannot be written in
/// the format (output_format.cpp).
void checkWritable(const OutputFormat& format, const std::string& dataType,
    const std::vector<std::string>& types, const std::string& compression, const std::string& path);

/// The OIIO error text of an input (or the global one), never empty.
std::string inputError(OIIO::ImageInput* in);

} // namespace afn::io::detail
