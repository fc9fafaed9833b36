// SPDX-License-Identifier: Apache-2.0
#include "filter/registry.h"

#include "base/exception.h"
#include "filter/quality.h"
#include "stages/detail_restore.h"
#include "stages/history_trust.h"

#include <algorithm>

namespace afn {

namespace {

void append(std::vector<ParamDesc>& to, std::vector<ParamDesc> from)
{
    for (ParamDesc& d : from)
        to.push_back(std::move(d));
}

/// The full parameter table of a method (order documented at FilterType::params).
FilterType registered(FilterType t)
{
    std::vector<ParamDesc> table;
    if (t.stages.accumulate)
        append(table, accumulationBinding().descriptors());
    append(table, std::move(t.params));
    if (!t.qualityHelp.empty())
        table.push_back(qualityDescriptor(t.qualityHelp));
    if (t.stages.reproject != StageNeeds::Reproject::None) {
        append(table, reprojectBinding().descriptors());
        append(table, historyTrustBinding().descriptors());
        t.features.push_back({ kHistoryTrustFeature, 1,
            "history trust per pixel (stages/history_trust.h): 1 where the reprojected history "
            "was kept, towards 0 where a change of the lighting cut it" });
    }
    if (t.stages.demodulate) {
        append(table, auxBinding().descriptors());
        append(table, restoreBinding().descriptors());
    }
    append(table, workDescriptors(t.skipHelp));
    append(table, conventionsBinding().descriptors());
    t.params = std::move(table);

    std::vector<InputUse> uses;
    if (t.stages.demodulate)
        uses.push_back({ { AFN_IMAGE_ALBEDO },
            "demodulation: texture detail is filtered together with the lighting" });
    for (InputUse& u : t.inputs)
        uses.push_back(std::move(u));
    if (t.stages.reproject != StageNeeds::Reproject::None)
        uses.push_back({ { AFN_IMAGE_MOTION, AFN_IMAGE_POSITION },
            "reprojection: without it the camera is taken as static", true });
    t.inputs = std::move(uses);
    return t;
}

std::string deviceName(AFNDeviceType type)
{
    return type == AFN_DEVICE_TYPE_CUDA ? "cuda" : "cpu";
}

} // namespace

const std::vector<FilterType>& filterTypes()
{
    static const std::vector<FilterType> types = {
        registered(identity::filterType()),
        registered(ta::filterType()),
        registered(svgf::filterType()),
        registered(bmfr::filterType()),
        registered(afnet::filterType()),
        registered(wskpn::filterType()),
        registered(nbgd::filterType()),
        registered(onnd::filterType()),
        registered(mrkp::filterType()),
    };
    return types;
}

const FilterType* findFilterType(const std::string& name)
{
    for (const FilterType& t : filterTypes())
        if (t.name == name)
            return &t;
    return nullptr;
}

std::unique_ptr<Filter> createFilter(const std::string& name, const Device& device)
{
    const FilterType* t = findFilterType(name);
    if (!t) {
        std::string known;
        for (const FilterType& k : filterTypes())
            known += (known.empty() ? "" : ", ") + k.name;
        throwInvalidArgument("unknown filter type '" + name + "' (known: " + known + ")");
    }
    if (std::find(t->devices.begin(), t->devices.end(), device.type()) == t->devices.end())
        throw Exception(AFN_ERROR_UNSUPPORTED,
            "method '" + name + "' does not run on the " + deviceName(device.type()) + " device");
    return t->create(*t, device);
}

std::unique_ptr<Filter> createFilter(const std::string& name)
{
    static const Device cpu(AFN_DEVICE_TYPE_CPU);
    return createFilter(name, cpu);
}

} // namespace afn
