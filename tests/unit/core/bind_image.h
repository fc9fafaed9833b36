// SPDX-License-Identifier: Apache-2.0
// A whole afn::Image (tightly packed float pixels) as the binding Filter::setImage takes: the one
// copy for the tests and benchmarks that drive a Filter directly (bench/ adds this folder to its
// include path).
#pragma once

#include "base/image.h"
#include "filter/filter.h"

#include <cstddef>

namespace afntest {

/// A binding of all of `img` for Filter::setImage.
inline afn::ImageBinding bindImage(afn::Image& img)
{
    afn::ImageBinding b;
    b.ptr = img.data();
    b.format = static_cast<AFNFormat>(img.channels());
    b.width = img.width();
    b.height = img.height();
    b.pixelStride = static_cast<std::ptrdiff_t>(img.channels() * sizeof(float));
    b.rowStride = b.pixelStride * img.width();
    return b;
}

} // namespace afntest
