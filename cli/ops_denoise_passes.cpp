// SPDX-License-Identifier: Apache-2.0
// --denoise:passes=: the light-path passes of a frame bound with the beauty (docs/passes.md).
#include "ops.h"

#include "cli_error.h"
#include "near_match.h"
#include "progress.h"
#include "text.h"

#include <algorithm>

namespace afntool {

void SequenceDenoiser::bindPasses(LoadedFrame& frame, Progress* progress)
{
    for (const std::string& name : m_passesBound) {
        m_filter.unsetImage((AFN_IMAGE_PASS_PREFIX + name).c_str());
        m_filter.unsetImage((AFN_IMAGE_PASS_FACTOR_PREFIX + name).c_str());
        m_filter.unsetImage((AFN_IMAGE_PASS_OUTPUT_PREFIX + name).c_str());
    }
    m_passesBound.clear();
    if (m_passes == "none")
        return;
    afn::io::FrameImages& img = frame.images;
    const afn::io::PassRecipe& recipe = img.passRecipe;
    std::vector<std::string> lights;
    for (const afn::io::LightPass& l : recipe.lights)
        lights.push_back(l.name);
    if (lights.empty())
        throw CliError(m_flag + ": :passes=" + m_passes
                + ": the file has no light passes this tool knows (see afntool --info; name them "
                  "with --aov lights=LAYER,LAYER*FACTOR)",
            frame.ref.path);
    std::vector<std::string> wanted = m_passes == "all" ? lights : splitList(m_passes, ',');
    for (const std::string& name : wanted) {
        const afn::io::LightPass* l = recipe.find(name);
        if (!l || std::find(lights.begin(), lights.end(), name) == lights.end()) {
            std::string list;
            for (const std::string& n : lights)
                list += (list.empty() ? "" : ", ") + n;
            throw CliError(m_flag + ": :passes= names '" + name + "', not a light pass of the file"
                    + didYouMean(name, lights) + " (light passes: " + list + ")",
                frame.ref.path);
        }
    }
    if (!m_recompositionChecked) {
        // Denoised passes add up to the denoised beauty only where the noisy ones add up to the
        // noisy beauty: said once, with the error.
        if (const auto r = afn::io::recompositionOf(img)) {
            const std::string warning = afn::io::recompositionWarning(recipe, *r);
            if (!warning.empty())
                warn(m_flag + ": " + warning + " (" + frame.ref.path
                        + "): the denoised passes will not add up to the denoised beauty either",
                    m_opts.quiet, progress);
        }
        m_recompositionChecked = true;
    }
    for (const std::string& name : wanted) {
        const afn::io::LightPass& l = *recipe.find(name);
        afn::io::RoleImage& p = img.passes.at(name);
        const std::size_t stride = p.components * sizeof(float);
        m_filter.setImage((AFN_IMAGE_PASS_PREFIX + name).c_str(), p.pixels.data(),
            afn::Format::Float3, p.width, p.height, 0, stride, 0);
        // In place: the denoised pass replaces the noisy one in the frame.
        m_filter.setImage((AFN_IMAGE_PASS_OUTPUT_PREFIX + name).c_str(), p.pixels.data(),
            afn::Format::Float3, p.width, p.height, 0, stride, 0);
        if (!l.factor.empty()) {
            afn::io::RoleImage& f = img.passes.at(l.factor);
            m_filter.setImage((AFN_IMAGE_PASS_FACTOR_PREFIX + name).c_str(), f.pixels.data(),
                afn::Format::Float3, f.width, f.height, 0, f.components * sizeof(float), 0);
        }
        m_passesBound.push_back(name);
    }
}

} // namespace afntool
