// SPDX-License-Identifier: Apache-2.0
// The AFN models by input set and the choice per frame (see methods/afn/model_set.h).
#include "methods/afn/model_set.h"

#include "base/exception.h"

#include <cmath>
#include <cstdlib>

extern "C" const unsigned char* const afnEmbeddedArchives[];
extern "C" const unsigned long long* const afnEmbeddedArchives_size[];
extern "C" const int afnEmbeddedArchives_count;

namespace afn::afnet {

void ModelSet::add(const nn::WeightsArchive& archive)
{
    const std::string& source = archive.source();
    Model m;
    const std::string key = archive.meta("inputs", inputSetKey(InputSet::full()));
    if (!parseInputSet(key, m.inputs))
        throwInvalidArgument("invalid or corrupted weights (" + source + "): unknown inputs '" + key
            + "' (expected color or a list of albedo, normal, depth, temporal)");
    const std::string spp = archive.meta("spp", "1");
    char* end = nullptr;
    const long count = std::strtol(spp.c_str(), &end, 10);
    if (spp.empty() || *end != '\0' || count < 1 || count > (1 << 20))
        throwInvalidArgument("invalid or corrupted weights (" + source + "): spp '" + spp
            + "' (expected the samples per pixel it was trained at, 1 to 1048576)");
    m.spp = static_cast<int>(count);
    m.net.load(archive);
    m_models.push_back(std::move(m));
}

ModelSet ModelSet::embedded()
{
    ModelSet set;
    for (int k = 0; k < afnEmbeddedArchives_count; ++k)
        set.add(nn::WeightsArchive::parse(afnEmbeddedArchives[k],
            static_cast<std::size_t>(*afnEmbeddedArchives_size[k]),
            "embedded AFN weights " + std::to_string(k)));
    return set;
}

ModelSet ModelSet::fromData(const void* data, std::size_t size)
{
    ModelSet set;
    set.add(nn::WeightsArchive::parse(data, size, "weights set with afnSetFilterData"));
    return set;
}

namespace {

std::string modelName(const Model& m)
{
    const std::string name = inputSetName(m.inputs);
    const std::string large = m.net.variant() == Variant::Large ? "AFN large" : "";
    if (m.spp == 1)
        return large.empty() ? name : name + " (" + large + ")";
    return name + " (" + std::to_string(m.spp) + " spp" + (large.empty() ? "" : ", " + large) + ")";
}

} // namespace

InputSet inputsToUse(const InputSet& available, const Model& model)
{
    InputSet use = model.inputs;
    use.temporal = use.temporal && available.temporal;
    return use;
}

Model* ModelSet::choose(const InputSet& available, int spp, bool allowLarge)
{
    auto eligible = [&](const Model& m) {
        return available.covers(inputsToUse(available, m))
            && (allowLarge || m.net.variant() != Variant::Large);
    };
    // The order: more inputs used; on a tie the temporal branch in use, then a model trained for
    // exactly the inputs it uses (a single-frame model before a temporal one run single-frame),
    // then the one listed first.
    auto before = [&](const Model& m, const Model& b) {
        const InputSet um = inputsToUse(available, m), ub = inputsToUse(available, b);
        if (um.count() != ub.count())
            return um.count() > ub.count();
        if (um.temporal != ub.temporal)
            return um.temporal;
        return m.inputs == um && !(b.inputs == ub);
    };
    Model* best = nullptr;
    for (Model& m : m_models)
        if (eligible(m) && (!best || before(m, *best)))
            best = &m;
    if (!best)
        return nullptr;
    // The sample count, among the models for the chosen input set.
    const double want = std::log2(static_cast<double>(spp > 1 ? spp : 1));
    auto distance = [&](const Model& m) { return std::fabs(std::log2(double(m.spp)) - want); };
    for (Model& m : m_models) {
        if (!eligible(m) || !(m.inputs == best->inputs) || &m == best)
            continue;
        const double dm = distance(m), db = distance(*best);
        if (dm < db || (dm == db && m.spp < best->spp))
            best = &m;
    }
    return best;
}

std::string ModelSet::listing() const
{
    std::string out;
    for (const Model& m : m_models)
        out += (out.empty() ? "" : "; ") + modelName(m);
    return out.empty() ? "none" : out;
}

void ModelSet::throwNoModelFor(const InputSet& available) const
{
    throwInvalidOperation("afn: no weights for the inputs " + inputSetName(available)
        + " (the models available are for: " + listing()
        + "); give weights trained for these inputs or a subset of them with "
          "afnSetFilterData(filter, \"weights\", data, size) (afntool: --weights FILE)");
}

namespace {

/// describePath's text with `label` naming the model; `temporalModel`: the model has a temporal
/// branch (which reads the current frame where `used` has no history).
std::string pathText(const InputSet& available, const InputSet& used, const std::string& label,
    bool temporalModel = false)
{
    std::string text = "model " + label;
    if (used.temporal)
        text += ", temporal";
    else if (temporalModel)
        text += ", single-frame (no motion or position: the temporal branch reads this frame)";
    else
        text += available.temporal ? ", single-frame (no temporal branch: the model has none)"
                                   : ", single-frame (no temporal branch: no motion or position)";
    const InputSet unused { available.albedo && !used.albedo, available.normal && !used.normal,
        available.depth && !used.depth, available.temporal && !used.temporal };
    if (unused.count() > 0)
        text += "; not used: " + inputSetKey(unused);
    return text;
}

} // namespace

std::string describeChoice(const InputSet& available, const Model& used)
{
    return pathText(available, inputsToUse(available, used), modelName(used), used.inputs.temporal);
}

std::string describePath(const InputSet& available, const InputSet& used)
{
    return pathText(available, used, inputSetName(used));
}

} // namespace afn::afnet
