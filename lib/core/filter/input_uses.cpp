// SPDX-License-Identifier: Apache-2.0
// Which of a method's inputs a frame lacks: every method runs on colour alone, but a method that
// reads albedo, normals, depth or motion degrades without them, and the caller should say so
// rather than run silently (afntool warns; AFN_STAT_MISSING_INPUTS).
#include "filter/filter.h"
#include "filter/registry.h"

namespace afn {

namespace {

bool frameHas(const Frame& f, const std::string& name, bool positionNeedsCamera)
{
    if (name == AFN_IMAGE_ALBEDO)
        return f.hasAlbedo();
    if (name == AFN_IMAGE_NORMAL)
        return f.hasNormal();
    if (name == AFN_IMAGE_DEPTH)
        return f.hasDepth();
    if (name == AFN_IMAGE_POSITION)
        return f.hasPosition() && (!positionNeedsCamera || f.camera.valid);
    if (name == AFN_IMAGE_MOTION)
        return f.hasMotion();
    return false;
}

} // namespace

std::string missingInputs(const FilterType& type, const Frame& frame)
{
    std::string text;
    for (const InputUse& use : type.inputs) {
        bool served = false;
        for (const std::string& name : use.anyOf)
            served = served || frameHas(frame, name, use.positionNeedsCamera);
        if (served)
            continue;
        std::string names;
        for (std::size_t i = 0; i < use.anyOf.size(); ++i) {
            names += (i == 0 ? "" : i + 1 == use.anyOf.size() ? " or " : ", ") + use.anyOf[i];
            if (use.anyOf[i] == AFN_IMAGE_POSITION && use.positionNeedsCamera)
                names += " with a camera";
        }
        text += (text.empty() ? "" : "; ") + names + " (" + use.purpose + ")";
    }
    return text;
}

} // namespace afn
