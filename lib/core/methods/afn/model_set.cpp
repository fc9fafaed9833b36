// SPDX-License-Identifier: Apache-2.0
// The AFN models by input set and the choice per frame (see methods/afn/model_set.h).
#include "methods/afn/model_set.h"

#include "base/exception.h"

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

Model* ModelSet::choose(const InputSet& available)
{
    Model* best = nullptr;
    for (Model& m : m_models) {
        if (!available.covers(m.inputs))
            continue;
        if (!best || m.inputs.count() > best->inputs.count()
            || (m.inputs.count() == best->inputs.count() && m.inputs.temporal
                && !best->inputs.temporal))
            best = &m;
    }
    return best;
}

std::string ModelSet::listing() const
{
    std::string out;
    for (const Model& m : m_models)
        out += (out.empty() ? "" : "; ") + inputSetName(m.inputs);
    return out.empty() ? "none" : out;
}

void ModelSet::throwNoModelFor(const InputSet& available) const
{
    throwInvalidOperation("afn: no weights for the inputs " + inputSetName(available)
        + " (the models available are for: " + listing()
        + "); give weights trained for these inputs or a subset of them with "
          "afnSetFilterData(filter, \"weights\", data, size) (afntool: --weights FILE)");
}

std::string describePath(const InputSet& available, const InputSet& used)
{
    std::string text = "model " + inputSetName(used);
    text += used.temporal ? ", temporal" : ", single-frame (no temporal branch";
    if (!used.temporal)
        text += available.temporal ? ": the model has none)" : ": no motion or position)";
    const InputSet unused { available.albedo && !used.albedo, available.normal && !used.normal,
        available.depth && !used.depth, available.temporal && !used.temporal };
    if (unused.count() > 0) {
        const std::string names = inputSetKey(unused);
        text += "; not used: " + names;
    }
    return text;
}

} // namespace afn::afnet
