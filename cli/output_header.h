// SPDX-License-Identifier: Apache-2.0
// What every afntool output records and keeps (oiiotool's and Nuke Write's conventions): the
// input's data and display windows and header metadata, `Software`, an `Exif:ImageHistory` entry
// naming what made the file (the method with every parameter in effect), the colour space, and
// the data type and colour encoding chosen for the output format.
#pragma once

#include "frame_loader.h"

#include "afn/io.hpp"

#include <string>

namespace afntool {

/// "afntool MAJOR.MINOR.PATCH", the Software attribute of every output.
std::string softwareName();

/// True for the integer types ("uint8", "uint16") that hold display-referred [0, 1] values.
bool isIntegerType(const std::string& type);

/// The type the output's format stores for the frame's beauty: -d when given, else the input's
/// (in the nearest type the format stores; `format` from afn::io::outputFormat()).
std::string outputDataType(
    const Options& opts, const LoadedFrame& frame, const afn::io::OutputFormat& format);

/// The colour space a beauty output is written in: --outcolorspace; else for integer outputs the
/// input's space when the input was an integer file too (round trips are exact), else the
/// config's space for integer files (display-referred, sRGB-encoded); for float outputs the
/// input's space when the input was float (scene-linear EXR stays as it was), else the working
/// space (an sRGB-encoded PNG is linearised).
std::string outputColorSpace(RunContext& ctx, const LoadedFrame& frame, const std::string& type);

/// Fill a write's header: the frame's windows and metadata, Software, the history entry ending
/// in `action` (e.g. "-o out.exr"), and (when `colorSpace` is set) oiio:ColorSpace plus, in
/// OpenEXR files, colorInteropID and chromaticities.
void describeOutput(RunContext& ctx, const LoadedFrame& frame, const std::string& action,
    const std::string& colorSpace, const afn::io::OutputFormat& format, afn::io::WriteOptions& wo);

} // namespace afntool
