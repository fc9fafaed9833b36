// SPDX-License-Identifier: Apache-2.0
// "bmfr": blockwise multi-order feature regression (bmfr.h) on albedo-demodulated colour.
#include "methods/bmfr/denoiser.h"
#include "stages/demodulate.h"
#include "filter/registry.h"

namespace afn::bmfr {

namespace {

class BmfrFilter final : public Filter {
public:
    explicit BmfrFilter(const std::vector<ParamDesc>* table)
        : Filter(table)
    {
    }

private:
    void configure() override
    {
        m_bmfr.setSettings(readBmfrSettings(params()), readReprojectSettings(params()));
    }
    void resetHistory() override { m_bmfr.reset(); }
    void denoise(const Frame& in, Image& out) override
    {
        demodulate(in, m_irradiance);
        m_bmfr.process(in, m_irradiance, out);
    }

    Denoiser m_bmfr;
    Image m_irradiance;
};

} // namespace

FilterType filterType()
{
    FilterType t;
    t.name = "bmfr";
    t.description = "blockwise multi-order feature regression (Koskela et al. 2019) with BMFR's "
                    "accumulations and TAA";
    t.params = bmfrParams();
    for (ParamDesc& d : reprojectParams())
        t.params.push_back(std::move(d));
    t.create = [](const std::vector<ParamDesc>* table) {
        return std::unique_ptr<Filter>(new BmfrFilter(table));
    };
    return t;
}

} // namespace afn::bmfr
