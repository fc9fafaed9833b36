// SPDX-License-Identifier: Apache-2.0
// The "afn Denoise" image effect: describe, instances, regions, frames needed, identity, render.
#pragma once

#include "ofx/ofx_api.h"

#include <string>

namespace afnofx {

/// Reverse-DNS identifier. Never change it: hosts save it in projects.
constexpr const char* kDenoiseIdentifier = "org.afn.Denoise";
/// Incrementing the major version means saved projects may no longer load the same way (a
/// parameter removed or its meaning changed); the minor version grows with compatible additions
/// (new methods or parameters, fixes).
constexpr unsigned int kDenoiseVersionMajor = 1;
constexpr unsigned int kDenoiseVersionMinor = 1;

/// Handle one OFX action of the effect; kOfxStatReplyDefault for actions it leaves to the host.
/// Throws OfxError (and std::exception) for failures; Main.cpp reports them.
OfxStatus denoiseAction(const std::string& action, OfxImageEffectHandle effect,
    OfxPropertySetHandle inArgs, OfxPropertySetHandle outArgs);

} // namespace afnofx
