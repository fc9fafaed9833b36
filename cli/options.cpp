// SPDX-License-Identifier: Apache-2.0
#include "options.h"

#include "cli_error.h"

#include "afn/afn.hpp"

#include <sstream>

namespace afntool {

std::string splitModifiers(const std::string& arg, std::map<std::string, std::string>& mods)
{
    std::size_t pos = arg.find(':');
    const std::string name = arg.substr(0, pos);
    while (pos != std::string::npos) {
        const std::size_t next = arg.find(':', pos + 1);
        const std::string item
            = arg.substr(pos + 1, next == std::string::npos ? next : next - pos - 1);
        const std::size_t eq = item.find('=');
        if (item.empty() || eq == 0)
            throw CliError("malformed modifier in '" + arg + "' (expected :key=value)");
        if (eq == std::string::npos)
            mods[item] = "1";
        else
            mods[item.substr(0, eq)] = item.substr(eq + 1);
        pos = next;
    }
    return name;
}

namespace {

const char* needValue(int& i, int argc, const char* const* argv, const std::string& flag)
{
    if (i + 1 >= argc)
        throw CliError(flag + " needs an argument");
    return argv[++i];
}

int parseInt(const std::string& text, const std::string& flag)
{
    try {
        std::size_t used = 0;
        const int v = std::stoi(text, &used);
        if (used != text.size())
            throw std::invalid_argument(text);
        return v;
    } catch (const std::exception&) {
        throw CliError(flag + " expects an integer, got '" + text + "'");
    }
}

} // namespace

Options parseCommandLine(int argc, const char* const* argv)
{
    Options o;
    for (int i = 1; i < argc; ++i) {
        const std::string raw = argv[i];
        if (raw.size() < 2 || raw[0] != '-') {
            o.inputs.push_back(raw);
            continue;
        }
        std::map<std::string, std::string> mods;
        const std::string flag = splitModifiers(raw, mods);
        if (flag == "-h" || flag == "--help") {
            o.help = true;
        } else if (flag == "--methods") {
            o.methods = true;
        } else if (flag == "--version") {
            o.version = true;
        } else if (flag == "--frames") {
            o.frames = needValue(i, argc, argv, flag);
        } else if (flag == "--colorconfig") {
            o.colorConfig = needValue(i, argc, argv, flag);
        } else if (flag == "--incolorspace") {
            o.inColorSpace = needValue(i, argc, argv, flag);
        } else if (flag == "--outcolorspace") {
            o.outColorSpace = needValue(i, argc, argv, flag);
        } else if (flag == "--aov") {
            try {
                afn::io::parseOverride(needValue(i, argc, argv, flag), o.overrides);
            } catch (const afn::io::IoError& e) {
                throw CliError(std::string("--aov: ") + e.what());
            }
        } else if (flag == "--threads") {
            o.threads = parseInt(needValue(i, argc, argv, flag), flag);
            if (o.threads < 0)
                throw CliError("--threads must be >= 0");
        } else if (flag == "--preroll") {
            o.preroll = parseInt(needValue(i, argc, argv, flag), flag);
            if (o.preroll < 0)
                throw CliError("--preroll must be >= 0, got " + std::to_string(o.preroll));
        } else if (flag == "--device") {
            o.device = needValue(i, argc, argv, flag);
            if (o.device != "cpu" && o.device != "cuda" && o.device != "auto")
                throw CliError("--device expects cpu, cuda or auto, got '" + o.device + "'");
        } else if (flag == "--weights") {
            o.weights = needValue(i, argc, argv, flag);
        } else if (flag == "-d") {
            o.dataType = needValue(i, argc, argv, flag);
            if (o.dataType != "half" && o.dataType != "float")
                throw CliError("-d expects half or float, got '" + o.dataType + "'");
        } else if (flag == "--compression") {
            o.compression = needValue(i, argc, argv, flag);
        } else if (flag == "--keep-aovs") {
            o.keepAovs = true;
        } else if (flag == "--json") {
            o.json = true;
        } else if (flag == "-q" || flag == "--quiet") {
            o.quiet = true;
        } else if (flag == "--info") {
            o.actions.push_back({ "info", "", mods });
        } else if (flag == "--denoise") {
            o.actions.push_back({ "denoise", "", mods });
        } else if (flag == "--features") {
            o.actions.push_back({ "features", needValue(i, argc, argv, flag), mods });
        } else if (flag == "--preview") {
            o.actions.push_back({ "preview", needValue(i, argc, argv, flag), mods });
        } else if (flag == "--contact-sheet") {
            o.actions.push_back({ "contact-sheet", needValue(i, argc, argv, flag), mods });
        } else if (flag == "--compare") {
            o.actions.push_back({ "compare", needValue(i, argc, argv, flag), mods });
        } else if (flag == "--benchmark") {
            o.actions.push_back({ "benchmark", "", mods });
        } else if (flag == "--report") {
            o.report = needValue(i, argc, argv, flag);
        } else if (flag == "-o") {
            o.actions.push_back({ "output", needValue(i, argc, argv, flag), mods });
        } else {
            throw CliError("unknown argument '" + raw + "' (see afntool --help)");
        }
    }
    return o;
}

static std::string paramLine(const AFNParamInfo& p)
{
    std::ostringstream os;
    os << "        " << p.name << "=";
    switch (p.type) {
    case AFN_PARAM_BOOL:
        os << (p.defaultValue != 0.0 ? "1" : "0") << "  (bool)";
        break;
    case AFN_PARAM_INT:
        os << p.defaultValue << "  (int " << p.minValue << ".." << p.maxValue << ")";
        break;
    case AFN_PARAM_FLOAT:
        os << p.defaultValue << "  (float " << p.minValue << ".." << p.maxValue << ")";
        break;
    case AFN_PARAM_STRING:
        os << p.defaultString << "  (" << p.choices << ")";
        break;
    }
    os << "\n            " << p.help << "\n";
    return os.str();
}

std::string methodsText()
{
    std::ostringstream os;
    for (const std::string& type : afn::filterTypes()) {
        const char* desc = afnGetFilterTypeDescription(type.c_str());
        os << type << (afn::isFilterTypeReady(type.c_str()) ? " ready " : " needs-weights ")
           << (desc ? desc : "") << "\n";
    }
    return os.str();
}

std::string helpText()
{
    std::ostringstream os;
    os << "afntool " << AFN_VERSION_MAJOR << "." << AFN_VERSION_MINOR << "." << AFN_VERSION_PATCH
       << " -- denoise path-traced renders (AFN, SVGF, BMFR, ...)\n\n"
       << "Usage: afntool [settings] INPUT [actions]\n"
       << "  INPUT is a file or a frame pattern (shot.####.exr: # = 4 digits, @ = 1 digit, %04d).\n"
       << "  Actions run per frame in the order given; ':key=value' modifiers follow an action.\n\n"
       << "Settings:\n"
       << "  --frames A-B            frame range for patterns (1-10, 1-10x2, 3,5,7)\n"
       << "  --preroll N             first run the N frames before the first of --frames through\n"
       << "                          --denoise/--features, unwritten, to rebuild their history\n"
       << "                          (farm chunks; stops at the sequence start; docs/farm.md)\n"
       << "  --aov ROLE=CHANNELS     map a role by hand: albedo=diffuse.R,diffuse.G,diffuse.B or\n"
       << "                          albedo=diffuse; conventions too: normal.space=camera\n"
       << "                          (roles: color albedo normal depth position motion alpha)\n"
       << "  --colorconfig FILE      OpenColorIO config (default: $OCIO, else afn's own)\n"
       << "  --incolorspace NAME     colour space of the input beauty (default: the file's, else\n"
       << "                          the working space)\n"
       << "  --outcolorspace NAME    colour space of written images (default: the input's)\n"
       << "  --threads N             worker threads (0 = all cores)\n"
       << "  --device cpu|cuda|auto  where --denoise runs (default cpu: the reference results,\n"
       << "                          the same on every machine). cuda: an NVIDIA GPU of compute\n"
       << "                          capability 9.0+ in builds with CUDA; only afn runs there\n"
       << "                          (half precision, within docs/gpu.md's tolerance of cpu).\n"
       << "                          auto: cuda when there is one and the method runs there,\n"
       << "                          else cpu with a note on stderr\n"
       << "  --weights FILE          network weights (.afnw) for learned methods such as afn,\n"
       << "                          instead of the ones built in (also :weights=FILE on "
          "--denoise)\n"
       << "  -d half|float           output data type (default: the input's)\n"
       << "  --compression NAME      EXR compression (zip, piz, dwaa, none, ...; default: "
          "input's)\n"
       << "  --keep-aovs             copy every other input layer into -o outputs\n"
       << "  --json                  machine-readable --info\n"
       << "  --methods               list the methods, each 'ready' or 'needs-weights'\n"
       << "  -q, --quiet             no progress bar and no warnings\n\n"
       << "Actions:\n"
       << "  --info                  layers, channels, windows, role mapping, per-role statistics\n"
       << "  --denoise:method=NAME[:param=value...]\n"
       << "                          denoise the sequence in frame order (history kept)\n"
       << "  --features[:method=afn] OUT.exr\n"
       << "                          the learned method's network inputs as it prepares them\n"
       << "                          (one float layer per feature; no weights needed)\n"
       << "  --preview OUT.png       display-referred beauty (:display=NAME:view=NAME)\n"
       << "  --contact-sheet OUT.png every AOV of the frame as a labelled tile\n"
       << "                          (:columns=4:tilesize=480)\n"
       << "  -o OUT                  write the beauty as top-level R,G,B[,A] (atomic)\n"
       << "  --compare REF           metrics of the current beauty against REF (file or pattern):\n"
       << "                          per frame and mean; table, or JSON with --json\n"
       << "  --benchmark:methods=ta,svgf/iterations=2,...  (with --compare REF [--report DIR])\n"
       << "                          time and score each method on the sequence; report folder "
          "with\n"
       << "                          results.json/.csv, runtime-vs-error.svg, index.html\n"
       << "                          (:repeat=N :error=rmse|psnr|ssim|smape|... :crop=X,Y,W,H\n"
       << "                          :crop-frames=F,G)\n"
       << "  --benchmark:size=1280x720,1920x1080,...  time the denoise stage on generated inputs\n"
       << "                          (:methods=a,b :frames=N :warmup=W; --json, --report DIR)\n"
       << "  --report DIR            folder for --benchmark's report files\n\n"
       << "Denoising methods and their parameters (name=default (type range)):\n";
    for (const std::string& type : afn::filterTypes()) {
        const char* desc = afnGetFilterTypeDescription(type.c_str());
        os << "  " << type << ": " << (desc ? desc : "")
           << (afn::isFilterTypeReady(type.c_str()) ? "" : " [needs weights: --weights FILE]")
           << "\n";
        for (const AFNParamInfo& p : afn::filterTypeParams(type.c_str())) {
            const std::string name = p.name;
            // Input conventions are set from the role mapping; list them once below.
            if (name.find('.') != std::string::npos)
                continue;
            os << paramLine(p);
        }
    }
    os << "  Input conventions (every method; set automatically from the role mapping,\n"
       << "  override with --aov or as modifiers):\n";
    if (!afn::filterTypes().empty()) {
        for (const AFNParamInfo& p : afn::filterTypeParams(afn::filterTypes().front().c_str()))
            if (std::string(p.name).find('.') != std::string::npos)
                os << paramLine(p);
    }
    os << "\nExamples:\n"
       << "  afntool --info --json render.exr\n"
       << "  afntool --frames 0-59 shot.####.exr --denoise:method=svgf -o out.####.exr\n"
       << "  afntool shot.0001.exr --contact-sheet aovs.png --preview beauty.png\n";
    return os.str();
}

} // namespace afntool
