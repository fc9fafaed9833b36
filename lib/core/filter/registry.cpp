// SPDX-License-Identifier: Apache-2.0
#include "filter/registry.h"

#include "base/exception.h"

namespace afn {

std::vector<ParamDesc> commonParams()
{
    return {
        choiceParam("normal.space", "world", "world|camera|camera-toward-viewer", "Normal space",
                    "space of the normal input: world, camera (+Z into the scene, Blender's "
                    "Denoising Normal) or camera-toward-viewer (+Z toward the viewer, V-Ray)"),
        choiceParam("depth.kind", "planar", "planar|radial", "Depth kind",
                    "planar camera-z depth or radial ray distance"),
        choiceParam("motion.direction", "to-previous", "to-previous|to-next", "Motion direction",
                    "motion vectors point to where the surface was (to-previous) or will be "
                    "(to-next; negated under a constant-velocity assumption)"),
        boolParam("motion.yUp", false, "Motion y up",
                  "motion y grows upward (Blender's Vector pass); false = y grows with the row"),
        choiceParam("motion.units", "pixels", "pixels|ndc|uv", "Motion units",
                    "pixels of the input resolution, NDC ([-1,1] across the frame) or UV ([0,1])"),
        floatParam("motion.scale", 1.0, 0.0, 1000.0, "Motion scale",
                   "factor applied to the motion vectors (a host's render scale)"),
        boolParam("color.demodulated", false, "Colour demodulated",
                  "the colour input is already divided by albedo (BMFR dataset)"),
    };
}

namespace {

FilterType withCommon(FilterType t)
{
    for (ParamDesc& d : commonParams()) t.params.push_back(std::move(d));
    return t;
}

} // namespace

const std::vector<FilterType>& filterTypes()
{
    static const std::vector<FilterType> types = {
        withCommon(identity::filterType()),
        withCommon(ta::filterType()),
        withCommon(svgf::filterType()),
        withCommon(bmfr::filterType()),
        withCommon(afnet::filterType()), // needs weights (embedded or set as data)
    };
    return types;
}

const FilterType* findFilterType(const std::string& name)
{
    for (const FilterType& t : filterTypes())
        if (t.name == name) return &t;
    return nullptr;
}

std::unique_ptr<Filter> createFilter(const std::string& name)
{
    const FilterType* t = findFilterType(name);
    if (!t) {
        std::string known;
        for (const FilterType& k : filterTypes()) known += (known.empty() ? "" : ", ") + k.name;
        throwInvalidArgument("unknown filter type '" + name + "' (known: " + known + ")");
    }
    return t->create(&t->params);
}

} // namespace afn
