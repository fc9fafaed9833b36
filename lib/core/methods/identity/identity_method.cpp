// SPDX-License-Identifier: Apache-2.0
// "identity": no denoising. The output is the sanitised input colour (NaN/Inf -> 0, negatives ->
// 0), which makes it the reference for I/O round trips and the plugin's pass-through.
#include "filter/registry.h"

namespace afn::identity {

namespace {

class IdentityFilter final : public Filter {
public:
    explicit IdentityFilter(const FilterType& t)
        : Filter(t)
    {
    }

private:
    void denoise(const Frame& in, Image& out) override { out = in.color; }
};

} // namespace

FilterType filterType()
{
    FilterType t;
    t.name = "identity";
    t.description = "no denoising: the sanitised noisy colour (for I/O checks and comparisons)";
    t.create = factoryOf<IdentityFilter>();
    t.skipHelp = "nothing to skip (the output is the input)";
    return t;
}

} // namespace afn::identity
