// SPDX-License-Identifier: Apache-2.0
#include "run_checks.h"

#include "cli_error.h"

#include "afn/afn.hpp"
#include "afn/color.hpp"
#include "afn/io.hpp"

#include <algorithm>
#include <filesystem>
#include <map>
#include <set>
#include <sys/stat.h>

namespace afntool {

namespace fs = std::filesystem;

namespace {

const char* outputFlag(const std::string& action)
{
    if (action == "output")
        return "-o";
    if (action == "preview")
        return "--preview";
    if (action == "contact-sheet")
        return "--contact-sheet";
    if (action == "features")
        return "--features";
    return nullptr;
}

std::string weightsOf(const Options& opts, const Action& a)
{
    auto it = a.mods.find("weights");
    return it != a.mods.end() ? it->second : opts.weights;
}

/// Identity of a file: device and inode when it exists, and its canonical path (symlinks
/// resolved as far as they exist).
struct FileId {
    bool exists = false;
    dev_t dev = 0;
    ino_t ino = 0;
    std::string canonical;
};

FileId identify(const std::string& path)
{
    FileId id;
    struct stat st { };
    if (::stat(path.c_str(), &st) == 0) {
        id.exists = true;
        id.dev = st.st_dev;
        id.ino = st.st_ino;
    }
    std::error_code ec;
    const fs::path c = fs::weakly_canonical(path, ec);
    id.canonical = ec ? fs::path(path).lexically_normal().string() : c.string();
    return id;
}

} // namespace

std::vector<ReadFile> filesRead(const Options& opts, const std::vector<FrameRef>& frames)
{
    std::vector<ReadFile> reads;
    for (const FrameRef& f : frames)
        reads.push_back({ f.path, "an input" });
    // A dataset folder's frames are pseudo paths: every file in it (and in its inputs/) is read.
    for (const std::string& input : opts.inputs) {
        std::error_code ec;
        if (!fs::is_directory(input, ec))
            continue;
        for (const fs::path& dir : { fs::path(input), fs::path(input) / "inputs" })
            for (const auto& e : fs::directory_iterator(dir, ec))
                if (e.is_regular_file(ec))
                    reads.push_back({ e.path().string(), "a file of the dataset folder" });
    }
    for (const Action& a : opts.actions) {
        if (a.name == "compare") {
            const bool pattern = afn::io::hasFramePattern(a.arg);
            for (const FrameRef& f : frames) {
                if (pattern && !f.numbered)
                    break; // reported by --compare itself
                reads.push_back({ pattern ? afn::io::expandFramePattern(a.arg, f.frame) : a.arg,
                    "the --compare reference" });
            }
        }
        if ((a.name == "denoise" || a.name == "features") && !weightsOf(opts, a).empty())
            reads.push_back({ weightsOf(opts, a), "the weights file" });
    }
    if (!opts.weights.empty())
        reads.push_back({ opts.weights, "the weights file" });
    const std::string config = afn::color::resolveConfig(opts.colorConfig).path;
    if (!config.empty())
        reads.push_back({ config, "the colour config" });
    return reads;
}

void checkOutputs(
    const Options& opts, const std::vector<FrameRef>& frames, const std::vector<ReadFile>& reads)
{
    std::map<std::pair<dev_t, ino_t>, const ReadFile*> byInode;
    std::map<std::string, const ReadFile*> byPath;
    for (const ReadFile& r : reads) {
        const FileId id = identify(r.path);
        if (id.exists)
            byInode.emplace(std::make_pair(id.dev, id.ino), &r);
        byPath.emplace(id.canonical, &r);
    }
    for (const Action& a : opts.actions) {
        const char* flag = outputFlag(a.name);
        if (!flag)
            continue;
        for (const FrameRef& f : frames) {
            const std::string out = outputPath(a.arg, f, frames.size(), flag);
            const FileId id = identify(out);
            const ReadFile* hit = nullptr;
            if (auto it = byInode.find({ id.dev, id.ino }); id.exists && it != byInode.end())
                hit = it->second;
            else if (auto p = byPath.find(id.canonical); p != byPath.end())
                hit = p->second;
            if (hit)
                throw CliError(std::string(flag) + " would overwrite " + hit->what
                        + (hit->path == out ? "" : " (" + hit->path + ")")
                        + "; afntool never writes over a file it reads",
                    out);
        }
        if (a.name != "output" || frames.empty())
            continue;
        const std::string first = outputPath(a.arg, frames.front(), frames.size(), flag);
        afn::io::OutputFormat format;
        try {
            format = afn::io::outputFormat(first);
        } catch (const afn::io::IoError& e) {
            throw CliError(std::string("-o: ") + e.what(), first);
        }
        auto join = [](const std::vector<std::string>& list) {
            std::string s;
            for (const std::string& x : list)
                s += (s.empty() ? "" : ", ") + x;
            return s;
        };
        if (!opts.dataType.empty()
            && std::find(format.dataTypes.begin(), format.dataTypes.end(), opts.dataType)
                == format.dataTypes.end()) {
            std::vector<std::string> valid; // the -d choices among the format's types
            for (const char* t : { "uint8", "uint16", "half", "float" })
                if (std::find(format.dataTypes.begin(), format.dataTypes.end(), t)
                    != format.dataTypes.end())
                    valid.push_back(t);
            throw CliError("-d " + opts.dataType + " cannot be stored in " + format.name
                    + " files (valid: " + join(valid) + ")",
                first);
        }
        if (!opts.compression.empty() && !format.acceptsCompression(opts.compression))
            throw CliError("--compression " + opts.compression + " is not available for "
                    + format.name + " files"
                    + (format.compressions.empty() ? " (the format has no compression choices)"
                                                   : " (valid: " + join(format.compressions) + ")"),
                first);
    }
}

void checkFrameOrder(const Options& opts, const std::vector<FrameRef>& frames)
{
    bool ascending = true;
    for (std::size_t i = 1; i < frames.size(); ++i)
        ascending = ascending && (!frames[i].numbered || frames[i].frame > frames[i - 1].frame);
    if (ascending)
        return;
    for (const Action& a : opts.actions) {
        if (a.name != "denoise" && a.name != "features")
            continue;
        auto m = a.mods.find("method");
        const std::string method = m != a.mods.end() ? m->second : "afn";
        bool temporal = false;
        for (const AFNParamInfo& p : afn::filterTypeParams(method.c_str()))
            temporal = temporal || std::string(p.name) == "positionLimit";
        if (temporal)
            throw CliError("--frames " + opts.frames + " is not in ascending order, but --" + a.name
                + ":method=" + method
                + " is temporal: it reprojects its history with motion vectors that point to the "
                  "previous frame in time, so running backwards would warp the history the "
                  "wrong way. Give the frames in ascending order (e.g. --frames 0-7), or "
                  "denoise each frame in its own afntool call");
    }
}

} // namespace afntool
