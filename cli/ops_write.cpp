// SPDX-License-Identifier: Apache-2.0
// -o, --preview and --contact-sheet: everything that writes pictures of a frame.
#include "ops.h"

#include "cli_error.h"
#include "contact_sheet_layers.h"
#include "output_header.h"

#include <map>
#include <set>

namespace afntool {

namespace {

using afn::io::Role;

void writeChecked(const std::string& path, int w, int h, const std::vector<std::string>& channels,
    const std::vector<float>& pixels, const afn::io::WriteOptions& wo,
    const std::vector<std::string>& types = {})
{
    try {
        afn::io::writeImageAtomic(path, w, h, channels, pixels.data(), wo, types);
    } catch (const afn::io::IoError& e) {
        throw CliError(e.what(), e.file().empty() ? path : e.file());
    }
}

/// Channel names (as in LayeredImage) that roles of the frame were read from (all roles, or only
/// the beauty's: colour and alpha).
std::set<std::string> roleChannelNames(
    const afn::io::FrameImages& img, const afn::io::LayeredImage& all, bool beautyOnly)
{
    std::set<std::string> used;
    for (const afn::io::RoleChannels& rc : img.mapping.roles) {
        if (beautyOnly && rc.role != Role::Color && rc.role != Role::Alpha)
            continue;
        for (const std::string& ch : rc.channels) {
            used.insert(ch);
            // Multi-part files name channels "<part>.<name>" in the layered image.
            for (const std::string& name : all.channels)
                if (name.size() > ch.size()
                    && name.compare(name.size() - ch.size(), ch.size(), ch) == 0
                    && name[name.size() - ch.size() - 1] == '.' && rc.subimage > 0)
                    used.insert(name);
        }
    }
    return used;
}

int componentsOf(const afn::io::RoleImage& r)
{
    return r.components;
}

afn::io::OutputFormat formatOf(const std::string& path)
{
    try {
        return afn::io::outputFormat(path);
    } catch (const afn::io::IoError& e) {
        throw CliError(e.what(), path);
    }
}

std::size_t npxOf(const afn::io::RoleImage& image)
{
    return static_cast<std::size_t>(image.width) * image.height;
}

/// Index in `all` of a file channel (parts after the first are named "<part>.<name>"), -1 if none.
int layeredIndex(const afn::io::LayeredImage& all, const std::string& channel)
{
    for (std::size_t c = 0; c < all.channels.size(); ++c)
        if (all.channels[c] == channel)
            return static_cast<int>(c);
    for (std::size_t c = 0; c < all.channels.size(); ++c) {
        const std::string& n = all.channels[c];
        if (n.size() > channel.size() + 1
            && n.compare(n.size() - channel.size() - 1, std::string::npos, "." + channel) == 0)
            return static_cast<int>(c);
    }
    return -1;
}

} // namespace

void writeOutput(RunContext& ctx, const LoadedFrame& frame, const std::string& path,
    const std::vector<std::string>& inputs)
{
    const Options& opts = ctx.options();
    const afn::io::RoleImage& color = frame.images.roles.at(Role::Color);
    const int w = color.width, h = color.height;
    auto alpha = frame.images.roles.find(Role::Alpha);
    const bool hasAlpha = alpha != frame.images.roles.end();
    const afn::io::OutputFormat format = formatOf(path);

    // Beauty into the output colour space: scene-linear for float files, display-referred
    // (sRGB-encoded) for integer ones, unless --outcolorspace says otherwise.
    const std::string beautyType = outputDataType(opts, frame, format);
    const std::string outSpace = outputColorSpace(ctx, frame, beautyType);
    std::vector<float> rgb = frame.beauty;
    try {
        ctx.color().convert(rgb.data(), w, h, 3, ctx.color().workingSpace(), outSpace);
    } catch (const afn::color::ColorError& e) {
        throw CliError(std::string("colour conversion: ") + e.what(), path);
    }

    std::vector<std::string> channels = { "R", "G", "B" };
    if (hasAlpha)
        channels.push_back("A");
    std::vector<std::string> types(channels.size(), beautyType);

    std::vector<int> extra; // indices into the layered image
    const afn::io::LayeredImage* all = frame.images.all ? &*frame.images.all : nullptr;
    if (opts.keepAovs && all) {
        const std::set<std::string> used = roleChannelNames(frame.images, *all, true);
        for (std::size_t c = 0; c < all->channels.size(); ++c) {
            const std::string& name = all->channels[c];
            if (used.count(name) || name == "R" || name == "G" || name == "B" || name == "A")
                continue;
            extra.push_back(static_cast<int>(c));
            channels.push_back(name);
            types.push_back(
                format.storedType(opts.dataType.empty() ? all->types[c] : opts.dataType));
        }
    }

    // Denoised light passes replace the noisy ones under their own names, back in the file's
    // colour space as the other layers.
    std::map<int, const float*> replaced; // layered channel index -> denoised values (3 apart)
    std::map<std::string, std::vector<float>> passValues;
    if (all)
        for (const std::string& name : frame.denoisedPasses) {
            const afn::io::LightPass* l = frame.images.passRecipe.find(name);
            const afn::io::RoleImage& p = frame.images.passes.at(name);
            std::vector<float>& v = passValues[name];
            v.resize(npxOf(p) * 3);
            for (std::size_t i = 0; i < npxOf(p); ++i)
                for (int c = 0; c < 3; ++c)
                    v[i * 3 + c] = p.pixels[i * p.components + c];
            try {
                ctx.color().convert(
                    v.data(), p.width, p.height, 3, ctx.color().workingSpace(), frame.colorSpace);
            } catch (const afn::color::ColorError& e) {
                throw CliError(std::string("colour conversion: ") + e.what(), path);
            }
            for (int c = 0; c < 3 && l; ++c) {
                const int index = layeredIndex(*all, l->channels[c]);
                if (index >= 0)
                    replaced[index] = v.data() + c;
            }
        }

    const std::size_t nch = channels.size(), npx = static_cast<std::size_t>(w) * h;
    std::vector<float> pixels(npx * nch);
    for (std::size_t i = 0; i < npx; ++i) {
        float* p = &pixels[i * nch];
        p[0] = rgb[i * 3 + 0];
        p[1] = rgb[i * 3 + 1];
        p[2] = rgb[i * 3 + 2];
        std::size_t k = 3;
        if (hasAlpha)
            p[k++] = alpha->second.pixels[i * componentsOf(alpha->second)];
        for (int c : extra) {
            auto r = replaced.find(c);
            p[k++] = r != replaced.end() ? r->second[i * 3]
                                         : all->pixels[i * all->channels.size() + c];
        }
    }

    afn::io::WriteOptions wo;
    wo.dataType = beautyType;
    // The input's compression carries over between EXRs; --compression was checked up front.
    wo.compression = !opts.compression.empty() ? opts.compression
        : format.name == frame.images.header.format
            && format.acceptsCompression(frame.images.header.compression)
        ? frame.images.header.compression
        : std::string();
    describeOutput(ctx, frame, "-o " + path, outSpace, format, wo);
    wo.inputs = inputs;
    writeChecked(path, w, h, channels, pixels, wo, types);
}

void writePreview(RunContext& ctx, const LoadedFrame& frame, const Action& action,
    const std::string& path, const std::vector<std::string>& inputs)
{
    const afn::io::RoleImage& color = frame.images.roles.at(Role::Color);
    std::vector<float> rgb = frame.beauty;
    auto get = [&](const char* k) {
        auto it = action.mods.find(k);
        return it == action.mods.end() ? std::string() : it->second;
    };
    try {
        ctx.color().toDisplay(
            rgb.data(), color.width, color.height, 3, {}, get("display"), get("view"));
    } catch (const afn::color::ColorError& e) {
        throw CliError(std::string("--preview: ") + e.what(), path);
    }
    afn::io::WriteOptions wo;
    std::string step = "--preview";
    for (const auto& [k, v] : action.mods)
        step += ":" + k + "=" + v;
    describeOutput(ctx, frame, step + " " + path, {}, formatOf(path), wo);
    wo.inputs = inputs;
    writeChecked(path, color.width, color.height, { "R", "G", "B" }, rgb, wo);
}

void writeContactSheet(RunContext& ctx, const LoadedFrame& frame, const Action& action,
    const std::string& path, const std::vector<std::string>& inputs)
{
    afn::color::ColorManager& cm = ctx.color();
    auto get = [&](const char* k, const std::string& def) {
        auto it = action.mods.find(k);
        return it == action.mods.end() ? def : it->second;
    };
    const std::string display = get("display", ""), view = get("view", "");
    std::vector<afn::color::Tile> tiles;
    try {
        const afn::io::RoleImage& color = frame.images.roles.at(Role::Color);
        tiles.push_back(afn::color::makeTile(cm, "color", "color (beauty)", color.width,
            color.height, 3, frame.beauty.data(), display, view));
        for (const afn::io::RoleChannels& rc : frame.images.mapping.roles) {
            if (rc.role == Role::Color)
                continue;
            auto it = frame.images.roles.find(rc.role);
            if (it == frame.images.roles.end())
                continue;
            const afn::io::RoleImage& r = it->second;
            std::string label = afn::io::roleName(rc.role);
            if (!rc.channels.empty())
                label += ": " + rc.channels.front().substr(0, rc.channels.front().rfind('.'));
            tiles.push_back(afn::color::makeTile(cm, afn::io::roleName(rc.role), label, r.width,
                r.height, r.components, r.pixels.data(), display, view));
        }
        // Every layer no role reads, shown by what its channels look like.
        if (frame.images.all) {
            const afn::io::LayeredImage& all = *frame.images.all;
            for (afn::color::Tile& t :
                otherLayerTiles(cm, all, roleChannelNames(frame.images, all, false), display, view))
                tiles.push_back(std::move(t));
        }
    } catch (const afn::color::ColorError& e) {
        throw CliError(std::string("--contact-sheet: ") + e.what(), path);
    }
    auto intModifier = [&](const char* key, const char* def, int min) {
        int v = 0;
        try {
            v = std::stoi(get(key, def));
        } catch (const std::exception&) {
            throw CliError(std::string("--contact-sheet:") + key + " expects an integer");
        }
        if (v < min)
            throw CliError(
                std::string("--contact-sheet:") + key + " must be >= " + std::to_string(min));
        return v;
    };
    const int columns = intModifier("columns", "4", 1);
    // Tiles at most 480x270 (downscaled with a box filter) so a 4K frame's sheet stays viewable.
    const int maxTile = intModifier("tilesize", "480", 16);
    for (afn::color::Tile& t : tiles)
        t = afn::color::fitTile(t, maxTile, maxTile * 9 / 16);
    int w = 0, h = 0;
    const std::vector<float> sheet = afn::color::layoutContactSheet(tiles, columns, w, h);
    afn::io::WriteOptions wo;
    wo.attributes["Software"] = softwareName();
    wo.attributes["Exif:ImageHistory"]
        = softwareName() + ": " + frame.ref.path + " --contact-sheet " + path;
    wo.inputs = inputs;
    writeChecked(path, w, h, { "R", "G", "B" }, sheet, wo);
}

} // namespace afntool
