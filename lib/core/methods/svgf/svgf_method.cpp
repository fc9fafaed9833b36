// SPDX-License-Identifier: Apache-2.0
// "svgf": spatiotemporal variance-guided filtering (svgf.h) on albedo-demodulated colour.
#include "stages/demodulate.h"
#include "filter/registry.h"
#include "methods/svgf/denoiser.h"

namespace afn::svgf {

namespace {

class SvgfFilter final : public Filter {
public:
    explicit SvgfFilter(const std::vector<ParamDesc>* table)
        : Filter(table)
    {
    }

private:
    void configure() override
    {
        m_svgf.setSettings(readSvgfSettings(params()), readReprojectSettings(params()));
    }
    void resetHistory() override { m_svgf.reset(); }
    void denoise(const Frame& in, Image& out) override
    {
        demodulate(in, m_irradiance);
        m_svgf.process(in, m_irradiance, m_filtered);
        remodulate(in, m_filtered, out);
    }

    Denoiser m_svgf;
    Image m_irradiance, m_filtered;
};

} // namespace

FilterType filterType()
{
    FilterType t;
    t.name = "svgf";
    t.description
        = "spatiotemporal variance-guided filtering (Schied et al. 2017), paper parameters";
    t.params = svgfParams();
    for (ParamDesc& d : reprojectParams())
        t.params.push_back(std::move(d));
    t.create = [](const std::vector<ParamDesc>* table) {
        return std::unique_ptr<Filter>(new SvgfFilter(table));
    };
    return t;
}

} // namespace afn::svgf
