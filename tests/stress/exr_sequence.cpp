// SPDX-License-Identifier: Apache-2.0
#include "exr_sequence.h"

#include <afn/io.hpp>

#include <cstdio>
#include <fstream>
#include <sstream>

namespace stress {

void writeExr(const std::string& path, const FrameData& frame)
{
    struct Layer {
        const char* role;
        std::vector<std::string> channels;
    };
    const Layer layers[] = { { "color", { "R", "G", "B" } }, { "alpha", { "A" } },
        { "albedo", { "albedo.R", "albedo.G", "albedo.B" } }, { "normal", { "N.X", "N.Y", "N.Z" } },
        { "depth", { "Z" } }, { "position", { "P.X", "P.Y", "P.Z" } },
        { "motion", { "motion.X", "motion.Y" } } };
    std::vector<std::string> names;
    std::vector<const std::vector<float>*> planes;
    for (const Layer& l : layers)
        if (frame.planes.count(l.role)) {
            for (const std::string& c : l.channels)
                names.push_back(c);
            planes.push_back(&frame.plane(l.role));
        }
    const std::size_t n = static_cast<std::size_t>(frame.width) * frame.height;
    std::vector<float> pixels;
    pixels.reserve(n * names.size());
    for (std::size_t i = 0; i < n; ++i)
        for (const std::vector<float>* p : planes) {
            const std::size_t comps = p->size() / n;
            for (std::size_t c = 0; c < comps; ++c)
                pixels.push_back((*p)[i * comps + c]);
        }
    afn::io::WriteOptions wo;
    wo.dataType = "float";
    afn::io::writeImageAtomic(path, frame.width, frame.height, names, pixels.data(), wo);
}

std::vector<std::string> writeExrSequence(
    const std::string& pattern, const std::vector<FrameData>& frames)
{
    std::vector<std::string> paths;
    for (std::size_t f = 0; f < frames.size(); ++f) {
        char name[4096];
        std::snprintf(name, sizeof name, pattern.c_str(), static_cast<int>(f));
        writeExr(name, frames[f]);
        paths.push_back(name);
    }
    return paths;
}

std::vector<float> readColor(const std::string& path)
{
    return afn::io::readFrame(path).roles.at(afn::io::Role::Color).pixels;
}

std::string fileBytes(const std::string& path)
{
    std::ifstream in(path, std::ios::binary);
    std::ostringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

} // namespace stress
