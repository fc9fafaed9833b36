// SPDX-License-Identifier: Apache-2.0
// Input sets of the afn method (see methods/afn/input_set.h).
#include "methods/afn/input_set.h"

#include "filter/frame.h"

namespace afn::afnet {

bool InputSet::covers(const InputSet& r) const
{
    return (albedo || !r.albedo) && (normal || !r.normal) && (depth || !r.depth)
        && (temporal || !r.temporal);
}

int InputSet::count() const
{
    return int(albedo) + int(normal) + int(depth) + int(temporal);
}

InputSet inputSetOf(const Frame& f)
{
    InputSet s;
    s.albedo = f.hasAlbedo();
    s.normal = f.hasNormal();
    s.depth = f.hasDepth();
    s.temporal = f.hasMotion() || (f.hasPosition() && f.camera.valid);
    return s;
}

namespace {

std::string joined(const InputSet& s, const char* sep)
{
    std::string out;
    auto add = [&](bool on, const char* word) {
        if (on)
            out += (out.empty() ? "" : sep) + std::string(word);
    };
    add(s.albedo, "albedo");
    add(s.normal, "normal");
    add(s.depth, "depth");
    add(s.temporal, "temporal");
    return out;
}

} // namespace

std::string inputSetName(const InputSet& s)
{
    const std::string rest = joined(s, "+");
    return rest.empty() ? "color" : "color+" + rest;
}

std::string inputSetKey(const InputSet& s)
{
    const std::string rest = joined(s, ",");
    return rest.empty() ? "color" : rest;
}

bool parseInputSet(const std::string& text, InputSet& set)
{
    InputSet s;
    std::size_t start = 0;
    while (start <= text.size()) {
        std::size_t end = text.find_first_of(",+", start);
        if (end == std::string::npos)
            end = text.size();
        std::string word = text.substr(start, end - start);
        while (!word.empty() && word.front() == ' ')
            word.erase(word.begin());
        while (!word.empty() && word.back() == ' ')
            word.pop_back();
        if (word == "albedo")
            s.albedo = true;
        else if (word == "normal")
            s.normal = true;
        else if (word == "depth")
            s.depth = true;
        else if (word == "temporal")
            s.temporal = true;
        else if (word != "color")
            return false;
        start = end + 1;
    }
    set = s;
    return true;
}

} // namespace afn::afnet
