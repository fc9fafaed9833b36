// SPDX-License-Identifier: Apache-2.0
// WSKPN's weight-sharing filter (Fan et al. 2021): per pixel q six weights w_i(q) =
// exp(clamp(logit_i(q), -20, 20)), shared by every centre pixel p whose i-th box window (3, 5,
// ..., 13) holds q: out_i(p) = sum_q w_i(q) c(q) / sum_q w_i(q), windows cut at the image edge
// (a denominator <= 1e-30 gives 0); the six results fused by softmax(fusion logits). The sums are
// separable box sums (rows, then columns) of the products, so the cost is independent of the
// window size's square.
#pragma once

#include "base/image.h"

namespace afn::wskpn {

/// out (w x h x 3) from the linear colour (3 ch) and the head (12 ch); `products` and `scratch`
/// are working buffers (reused between calls).
void weightSharingFilter(
    const Image& color, const Image& head, Image& products, Image& scratch, Image& out);

} // namespace afn::wskpn
