// SPDX-License-Identifier: Apache-2.0
#include "ops.h"

#include "cli_error.h"
#include "info_afn_model.h"
#include "json_writer.h"

#include <algorithm>
#include <cstdio>
#include <optional>
#include <sstream>

namespace afntool {

namespace {

using afn::io::Role;

std::string join(const std::vector<std::string>& v, const char* sep = ", ")
{
    std::string out;
    for (std::size_t i = 0; i < v.size(); ++i)
        out += (i ? sep : "") + v[i];
    return out;
}

std::string boxText(const afn::io::Box& b)
{
    std::ostringstream os;
    os << b.width << "x" << b.height << " at (" << b.x << ", " << b.y << ")";
    return os.str();
}

struct FileReport {
    std::string path;
    afn::io::FileInfo info;
    afn::io::RoleMapping mapping;
    std::map<Role, afn::io::RoleStats> stats;
    std::map<Role, AFNAuxNoise> noise; ///< auxiliary roles only (afnEstimateAuxNoise)
    std::optional<int> samples;
    std::string afnModel; ///< the afn method's path for these inputs ("" without a colour)
    std::string afnNetwork; ///< the network's arithmetic on this CPU ("" where not known)
    afn::io::PassRecipe passes; ///< light-path passes and how they rebuild the beauty
    std::optional<afn::io::Recomposition> recomposition; ///< their sum against the beauty
};

/// The auxiliary roles whose noise --info estimates, with their afnEstimateAuxNoise names.
const std::pair<Role, const char*> kAuxRoles[] = { { Role::Albedo, AFN_IMAGE_ALBEDO },
    { Role::Normal, AFN_IMAGE_NORMAL }, { Role::Depth, AFN_IMAGE_DEPTH } };

/// Noise estimates of the frame's auxiliary roles (the numbers "aux=auto" decides on).
void estimateNoise(const afn::io::FrameImages& fi, std::map<Role, AFNAuxNoise>& out)
{
    afn::DeviceRef device = afn::newDevice();
    if (!device)
        throw CliError("cannot create an afn device");
    device.commit();
    for (const auto& [role, name] : kAuxRoles) {
        auto it = fi.roles.find(role);
        if (it == fi.roles.end())
            continue;
        const afn::io::RoleImage& img = it->second;
        AFNAuxNoise n {};
        if (!afnEstimateAuxNoise(device.getHandle(), name, img.pixels.data(), img.width, img.height,
                img.components, &n)) {
            std::string message;
            device.getError(&message);
            throw CliError("--info: " + message);
        }
        out[role] = n;
    }
}

/// The albedo or the normal has speckle above aux=auto's threshold (afnEstimateAuxNoise).
bool speckled(const FileReport& r)
{
    for (Role role : { Role::Albedo, Role::Normal }) {
        auto it = r.noise.find(role);
        if (it != r.noise.end() && it->second.noisy)
            return true;
    }
    return false;
}

bool trustedSampleCount(const FileReport& r)
{
    return r.samples && *r.samples >= AFN_AUX_TRUSTED_SPP;
}

/// What aux=auto would decide for this frame: noisy when the albedo or the normal is, below
/// AFN_AUX_TRUSTED_SPP samples per pixel (the file's count; unknown counts as low).
bool autoNoisy(const FileReport& r)
{
    return speckled(r) && !trustedSampleCount(r);
}

/// aux=auto's choice in words: from AFN_AUX_TRUSTED_SPP samples, buffers with speckle are used as
/// given with the albedo's grain limited over time (lib/core/stages/aux_prefilter.h).
std::string autoChoice(const FileReport& r)
{
    if (!speckled(r))
        return "clean";
    return trustedSampleCount(r) ? "clean, albedo grain limited" : "noisy";
}

FileReport collect(const Options& opts, const FrameRef& ref)
{
    FileReport r;
    r.path = ref.path;
    try {
        afn::io::ReadOptions ro;
        ro.overrides = opts.overrides;
        ro.required = {};
        ro.passes = true;
        const afn::io::FrameImages fi = afn::io::readFrame(ref.path, ro);
        r.mapping = fi.mapping;
        r.passes = fi.passRecipe;
        r.recomposition = afn::io::recompositionOf(fi);
        r.samples = fi.samples;
        for (const auto& [role, image] : fi.roles)
            r.stats[role] = afn::io::computeStats(image);
        estimateNoise(fi, r.noise);
        if (fi.roles.count(Role::Color))
            r.afnModel = afnModelFor(opts, fi, &r.afnNetwork);
        if (ref.path.find("#bmfr:") == std::string::npos) {
            r.info = afn::io::inspect(ref.path);
        } else {
            r.info.path = ref.path;
            r.info.format = "bmfr";
        }
    } catch (const afn::io::IoError& e) {
        throw CliError(e.what(), e.file().empty() ? ref.path : e.file());
    }
    return r;
}

/// The light-path passes, their roles and whether they add up to the beauty.
void printPasses(const FileReport& r)
{
    const afn::io::PassRecipe& p = r.passes;
    if (p.empty() && p.missing.empty()) {
        std::printf("  light passes: none (name them with --aov lights=LAYER,LAYER*FACTOR)\n");
        return;
    }
    std::printf("  light passes (%s): %s\n", p.renderer.c_str(), p.formula.c_str());
    for (const afn::io::LightPass& l : p.lights)
        std::printf("    light     %-22s %s%s\n", l.name.c_str(), join(l.channels).c_str(),
            l.factor.empty() ? "" : ("  (x " + l.factor + ")").c_str());
    for (const afn::io::LightPass& f : p.factors)
        std::printf("    factor    %-22s %s  (albedo-like: not denoised)\n", f.name.c_str(),
            join(f.channels).c_str());
    if (r.recomposition)
        std::printf(
            "    recomposition: PSNR %.1f dB against the beauty (tone-mapped), relative RMS "
            "error %.3g, largest difference %.4g\n",
            r.recomposition->psnr, r.recomposition->relativeRms, r.recomposition->maxAbsolute);
    const std::string warning = r.recomposition
        ? afn::io::recompositionWarning(p, *r.recomposition)
        : afn::io::recompositionWarning(p, afn::io::Recomposition { 1e9, 0, 0, 0 });
    if (!warning.empty())
        std::printf("    WARNING: %s\n", warning.c_str());
}

void printText(const FileReport& r)
{
    std::printf("%s\n", r.path.c_str());
    std::printf("  format: %s, renderer: %s, samples per pixel: %s\n", r.info.format.c_str(),
        r.mapping.renderer.c_str(), r.samples ? std::to_string(*r.samples).c_str() : "unknown");
    for (std::size_t s = 0; s < r.info.subimages.size(); ++s) {
        const afn::io::SubimageInfo& si = r.info.subimages[s];
        std::printf("  subimage %zu%s%s: data window %s, display window %s, compression %s\n", s,
            si.name.empty() ? "" : " ", si.name.c_str(), boxText(si.dataWindow).c_str(),
            boxText(si.displayWindow).c_str(), si.compression.c_str());
        std::printf("    %zu channels:", si.channels.size());
        for (std::size_t c = 0; c < si.channels.size(); ++c)
            std::printf("%s %s (%s)", c ? "," : "", si.channels[c].c_str(),
                c < si.types.size() ? si.types[c].c_str() : "?");
        std::printf("\n");
    }
    if (r.mapping.presetsTried.empty())
        std::printf("  roles:\n");
    else
        std::printf("  roles (%s names):\n", join(r.mapping.presetsTried, " names, then ").c_str());
    for (int i = 0; i < afn::io::kNumRoles; ++i) {
        const Role role = static_cast<Role>(i);
        const afn::io::RoleChannels* rc = r.mapping.find(role);
        if (rc) {
            std::printf("    %-9s %s  [%s]\n", afn::io::roleName(role), join(rc->channels).c_str(),
                rc->source.c_str());
            auto st = r.stats.find(role);
            if (st != r.stats.end())
                std::printf("              min %.6g  max %.6g  mean %.6g  NaN %lld  Inf %lld  "
                            "negative %lld\n",
                    st->second.min, st->second.max, st->second.mean, st->second.nan, st->second.inf,
                    st->second.negative);
            auto nz = r.noise.find(role);
            if (nz != r.noise.end())
                std::printf("              noise: speckle %.2f %% of pixels (%s)\n",
                    100.0 * nz->second.speckle, nz->second.noisy ? "noisy" : "clean");
        } else {
            // One short line: the names actually tried (the file's own channels are listed
            // above), at most kMaxNames of them.
            constexpr std::size_t kMaxNames = 6;
            auto lf = r.mapping.lookedFor.find(role);
            std::vector<std::string> names;
            if (lf != r.mapping.lookedFor.end())
                names = lf->second;
            const std::size_t more = names.size() > kMaxNames ? names.size() - kMaxNames : 0;
            names.resize(std::min(names.size(), kMaxNames));
            if (names.empty()) {
                std::printf("    %-9s (not found; name it with --aov %s=CHANNELS)\n",
                    afn::io::roleName(role), afn::io::roleName(role));
                continue;
            }
            std::string tried = join(names);
            if (more)
                tried += ", ... (" + std::to_string(more) + " more)";
            std::printf(
                "    %-9s (not found; looked for %s)\n", afn::io::roleName(role), tried.c_str());
        }
    }
    printPasses(r);
    std::printf("  aux=auto: %s\n", autoChoice(r).c_str());
    if (!r.afnModel.empty())
        std::printf("  afn: %s\n", r.afnModel.c_str());
    if (!r.afnNetwork.empty())
        std::printf("  afn network: %s\n", r.afnNetwork.c_str());
    std::printf("  conventions:");
    for (const auto& [name, value] : r.mapping.tag.parameters())
        std::printf(" %s=%s", name.c_str(), value.c_str());
    std::printf("\n");
}

void writeBox(JsonWriter& j, const char* key, const afn::io::Box& b)
{
    j.key(key)
        .beginObject()
        .field("x", b.x)
        .field("y", b.y)
        .field("width", b.width)
        .field("height", b.height)
        .endObject();
}

void writeJson(JsonWriter& j, const FileReport& r)
{
    j.beginObject();
    j.field("file", r.path);
    j.field("format", r.info.format);
    j.field("renderer", r.mapping.renderer);
    if (r.samples)
        j.field("samples", *r.samples);
    else
        j.key("samples").null();
    const afn::io::SubimageInfo* first = r.info.subimages.empty() ? nullptr : &r.info.subimages[0];
    j.field("width", first ? first->dataWindow.width : 0);
    j.field("height", first ? first->dataWindow.height : 0);
    std::vector<std::string> all;
    for (const auto& si : r.info.subimages)
        for (const auto& c : si.channels)
            all.push_back(si.name.empty() || r.info.subimages.size() == 1 ? c : si.name + "." + c);
    j.key("channels").value(all);
    j.key("subimages").beginArray();
    for (const auto& si : r.info.subimages) {
        j.beginObject();
        j.field("name", si.name);
        writeBox(j, "dataWindow", si.dataWindow);
        writeBox(j, "displayWindow", si.displayWindow);
        j.key("channels").value(si.channels);
        j.key("types").value(si.types);
        j.field("compression", si.compression);
        j.endObject();
    }
    j.endArray();
    j.key("roles").beginObject();
    for (const auto& rc : r.mapping.roles)
        j.key(afn::io::roleName(rc.role)).value(rc.channels);
    j.endObject();
    j.key("presetsTried").value(r.mapping.presetsTried);
    j.key("missingRoles").beginObject();
    for (const auto& [role, looked] : r.mapping.lookedFor)
        j.key(afn::io::roleName(role)).value(looked);
    j.endObject();
    const afn::io::SpaceTag& t = r.mapping.tag;
    j.key("conventions").beginObject();
    for (const auto& [name, value] : t.parameters()) {
        if (value == "true" || value == "false")
            j.field(name, value == "true");
        else
            j.field(name, value);
    }
    j.endObject();
    j.key("auxNoise").beginObject();
    for (const auto& [role, n] : r.noise)
        j.key(afn::io::roleName(role))
            .beginObject()
            .field("speckle", n.speckle)
            .field("noisy", n.noisy)
            .endObject();
    j.endObject();
    j.field("auxAuto", std::string(autoNoisy(r) ? "noisy" : "clean"));
    j.field("afnModel", r.afnModel);
    j.field("afnNetwork", r.afnNetwork);
    j.key("lightPasses").beginObject();
    j.field("recipe", r.passes.renderer);
    j.field("formula", r.passes.formula);
    j.key("lights").beginArray();
    for (const afn::io::LightPass& l : r.passes.lights)
        j.beginObject()
            .field("name", l.name)
            .field("factor", l.factor)
            .field("channels", l.channels)
            .endObject();
    j.endArray();
    j.key("factors").beginArray();
    for (const afn::io::LightPass& f : r.passes.factors)
        j.beginObject().field("name", f.name).field("channels", f.channels).endObject();
    j.endArray();
    j.key("missing").value(r.passes.missing);
    if (r.recomposition)
        j.field("recompositionPsnr", r.recomposition->psnr)
            .field("recompositionMaxDifference", r.recomposition->maxAbsolute)
            .field("recompositionRelativeRms", r.recomposition->relativeRms);
    j.endObject();
    j.key("stats").beginObject();
    for (const auto& [role, s] : r.stats) {
        j.key(afn::io::roleName(role))
            .beginObject()
            .field("min", s.min)
            .field("max", s.max)
            .field("mean", s.mean)
            .field("nan", s.nan)
            .field("inf", s.inf)
            .field("negative", s.negative)
            .field("count", s.count)
            .endObject();
    }
    j.endObject();
    j.endObject();
}

} // namespace

void runInfo(RunContext& ctx, const std::vector<FrameRef>& frames)
{
    const Options& opts = ctx.options();
    std::vector<FileReport> reports;
    for (const FrameRef& ref : frames)
        reports.push_back(collect(opts, ref));
    if (!opts.json) {
        for (const FileReport& r : reports)
            printText(r);
        return;
    }
    JsonWriter j;
    if (reports.size() == 1) {
        writeJson(j, reports[0]);
    } else {
        j.beginArray();
        for (const FileReport& r : reports)
            writeJson(j, r);
        j.endArray();
    }
    std::printf("%s\n", j.str().c_str());
}

} // namespace afntool
