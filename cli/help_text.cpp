// SPDX-License-Identifier: Apache-2.0
#include "help_text.h"

#include "cli_error.h"
#include "near_match.h"

#include "afn/afn.hpp"

#include <algorithm>
#include <sstream>

namespace afntool {

namespace {

std::string versionLine()
{
    std::ostringstream os;
    os << "afntool " << AFN_VERSION_MAJOR << "." << AFN_VERSION_MINOR << "." << AFN_VERSION_PATCH
       << " -- denoise path-traced renders (AFN, SVGF, BMFR, ...)\n";
    return os.str();
}

const char* kUsage = "Usage: afntool [settings] INPUT [actions]\n"
                     "  INPUT: a file, a frame pattern (shot.####.exr with --frames 1-10) or a\n"
                     "  BMFR dataset folder. Actions run per frame in the order given and take\n"
                     "  ':key=value' modifiers (--denoise:method=svgf:iterations=4).\n";

bool isConvention(const AFNParamInfo& p)
{
    return std::string(p.name).find('.') != std::string::npos;
}

std::string paramLine(const AFNParamInfo& p)
{
    std::ostringstream os;
    os << "  " << p.name << "=";
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
    os << "\n      " << p.help << "\n";
    return os.str();
}

} // namespace

std::string usageText()
{
    return versionLine() + "\n" + kUsage
        + "\nExample: afntool --frames 0-59 shot.####.exr --denoise:method=svgf -o out.####.exr\n"
          "More: afntool --help (options), afntool --help METHOD (its parameters)\n";
}

std::string helpText()
{
    std::ostringstream os;
    os << versionLine() << "\n"
       << kUsage << "\n"
       << "Actions:\n"
       << "  --info                  channels, AOV roles found, statistics (--json: as JSON)\n"
       << "  --denoise:method=NAME   denoise in frame order; :param=value (--help NAME);\n"
       << "                          :mask=CHANNEL (only where > 0); :passes=all|NAME,...\n"
       << "  -o OUT                  write the beauty (never over an input; atomic)\n"
       << "  --preview OUT.png       display-referred beauty (:display=NAME:view=NAME)\n"
       << "  --contact-sheet OUT.png every AOV as a labelled tile (:columns=4:tilesize=480)\n"
       << "  --compare REF           error metrics against a reference file or pattern\n"
       << "  --features OUT.exr      network inputs, history trust (:method=afn)\n"
       << "  --benchmark:methods=a,b time and score methods (with --compare REF, --report DIR;\n"
       << "                          or :size=1920x1080 on generated frames, :sky=0.6 skipping)\n"
       << "Settings:\n"
       << "  --frames A-B            frames of a pattern (1-10, 1-10x2, 3,5,7)\n"
       << "  --preroll N             rebuild the history from N unwritten frames (docs/farm.md)\n"
       << "  --aov ROLE=CHANNELS     name a role's channels (albedo=diffuse, or\n"
       << "                          albedo=d.R,d.G,d.B), ROLE=none, a convention\n"
       << "                          (normal.space=world) or lights=A,B*F (light passes)\n"
       << "  --colorconfig FILE      OpenColorIO config (default: $OCIO, else afn's own)\n"
       << "  --incolorspace NAME     colour space of the input (default: the file's)\n"
       << "  --outcolorspace NAME    colour space of written images (default: the input's)\n"
       << "  -d TYPE                 uint8|uint16|half|float (default: nearest to the input's)\n"
       << "  --compression NAME      output compression, checked against the format (EXR: zip,\n"
       << "                          piz, dwaa, none, ...; default: the input's EXR compression)\n"
       << "  --keep-aovs             copy the other input layers into -o outputs\n"
       << "  --device cpu|cuda|auto  where --denoise runs (default cpu; only afn runs there)\n"
       << "  --weights FILE          network weights (.afnw) instead of the built-in ones\n"
       << "  --threads N             worker threads (0 = all cores)\n"
       << "  -q, --quiet | -v        no progress, warnings or summary | every frame's detail\n"
       << "Methods (--help METHOD lists its parameters; --methods: which can run):\n";
    for (const std::string& type : afn::filterTypes()) {
        std::string desc = afnGetFilterTypeDescription(type.c_str());
        const std::size_t cut = desc.find_first_of("(,;");
        if (cut != std::string::npos && cut > 20)
            desc = desc.substr(0, cut);
        while (!desc.empty() && desc.back() == ' ')
            desc.pop_back();
        os << "  " << type << std::string(type.size() < 10 ? 10 - type.size() : 1, ' ') << desc
           << (afn::isFilterTypeReady(type.c_str()) ? "" : " [needs --weights]") << "\n";
    }
    os << "Examples:\n"
       << "  afntool --info render.exr\n"
       << "  afntool --frames 0-59 shot.####.exr --denoise:method=svgf -o out.####.exr\n";
    return os.str();
}

std::vector<std::string> helpTopics()
{
    return afn::filterTypes();
}

std::string topicHelpText(const std::string& topic)
{
    const std::vector<std::string> topics = helpTopics();
    if (std::find(topics.begin(), topics.end(), topic) == topics.end())
        throw CliError("--help: unknown method '" + topic + "'" + didYouMean(topic, topics)
            + " (methods: " + joinNames(topics) + ")");
    std::ostringstream os;
    const char* desc = afnGetFilterTypeDescription(topic.c_str());
    os << topic << ": " << (desc ? desc : "") << "\n";
    if (!afn::isFilterTypeReady(topic.c_str()))
        os << "Needs network weights: --weights FILE (this build embeds none).\n";
    os << "\nUsage: afntool ... --denoise:method=" << topic << "[:param=value...] ...\n"
       << "\nParameters (name=default  (type range)):\n";
    std::vector<AFNParamInfo> conventions;
    for (const AFNParamInfo& p : afn::filterTypeParams(topic.c_str())) {
        if (isConvention(p))
            conventions.push_back(p);
        else
            os << paramLine(p);
    }
    if (!conventions.empty()) {
        os << "\nInput conventions (set from the file's AOVs; override with --aov or as "
              "modifiers):\n";
        for (const AFNParamInfo& p : conventions)
            os << paramLine(p);
    }
    const std::vector<AFNFeatureInfo> features = afn::filterTypeFeatures(topic.c_str());
    if (!features.empty()) {
        os << "\nFeature outputs (--features:method=" << topic << " OUT.exr):\n";
        for (const AFNFeatureInfo& f : features)
            os << "  " << f.name << " (" << f.channels << " ch): " << f.help << "\n";
    }
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

} // namespace afntool
