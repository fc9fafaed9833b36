// SPDX-License-Identifier: Apache-2.0
// "ta": BMFR temporal accumulation only. Output = albedo-remodulated accumulated irradiance (the
// TA-1spp input of AFN, WSKPN and NBGD, remodulated).
#include "stages/demodulate.h"
#include "filter/registry.h"
#include "stages/temporal_accumulation.h"

namespace afn::ta {

namespace {

class TaFilter final : public Filter {
public:
    explicit TaFilter(const std::vector<ParamDesc>* table)
        : Filter(table)
    {
    }

private:
    void configure() override
    {
        m_reproject.setSettings(readReprojectSettings(params()));
        m_ta.setAlphaMin(params().getFloat("alphaMin"));
    }
    void resetHistory() override
    {
        m_reproject.reset();
        m_ta.reset();
    }
    void denoise(const Frame& in, Image& out) override
    {
        if (in.frameIndex == 0)
            resetHistory();
        demodulate(in, m_irradiance);
        m_reproject.compute(in);
        m_ta.accumulate(m_reproject, m_irradiance);
        m_reproject.storeGeometry(in);
        remodulate(in, m_ta.color(), out);
    }

    Reprojector m_reproject;
    TemporalAccumulator m_ta;
    Image m_irradiance;
};

} // namespace

FilterType filterType()
{
    FilterType t;
    t.name = "ta";
    t.description = "temporal accumulation only, exactly as BMFR (bilinear reprojection, per-tap "
                    "position/normal acceptance, alpha = max(1/(n+1), alphaMin))";
    t.params = { floatParam("alphaMin", 0.2, 0.0, 1.0, "Minimum blend factor",
        "weight of the current frame once the history is long (BMFR: 0.2)") };
    for (ParamDesc& d : reprojectParams())
        t.params.push_back(std::move(d));
    t.create = [](const std::vector<ParamDesc>* table) {
        return std::unique_ptr<Filter>(new TaFilter(table));
    };
    return t;
}

} // namespace afn::ta
