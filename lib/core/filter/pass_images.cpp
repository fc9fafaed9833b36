// SPDX-License-Identifier: Apache-2.0
#include "filter/pass_images.h"

#include "base/exception.h"

#include <cstring>

namespace afn {
namespace {

/// The pass name of `image` when it starts with `prefix`; "" otherwise.
std::string passNameOf(const std::string& image, const char* prefix)
{
    const std::size_t len = std::strlen(prefix);
    return image.size() > len && image.compare(0, len, prefix) == 0 ? image.substr(len)
                                                                    : std::string();
}

} // namespace

bool isPassImageName(const std::string& name)
{
    return !passNameOf(name, AFN_IMAGE_PASS_PREFIX).empty()
        || !passNameOf(name, AFN_IMAGE_PASS_FACTOR_PREFIX).empty()
        || !passNameOf(name, AFN_IMAGE_PASS_OUTPUT_PREFIX).empty();
}

void validatePassImages(const std::map<std::string, ImageBinding>& images, bool outputBound)
{
    for (const auto& [name, b] : images) {
        if (isPassImageName(name) && b.channels() < 3)
            throwInvalidArgument("image '" + name + "' needs at least 3 channels");
        const std::string pass = passNameOf(name, AFN_IMAGE_PASS_PREFIX);
        const std::string factor = passNameOf(name, AFN_IMAGE_PASS_FACTOR_PREFIX);
        const std::string out = passNameOf(name, AFN_IMAGE_PASS_OUTPUT_PREFIX);
        if (!factor.empty() && !images.count(AFN_IMAGE_PASS_PREFIX + factor))
            throwInvalidArgument("image '" + name + "' has no pass 'pass." + factor + "'");
        if (!out.empty() && !images.count(AFN_IMAGE_PASS_PREFIX + out))
            throwInvalidArgument("image '" + name + "' has no pass 'pass." + out + "'");
        if (!pass.empty() && !images.count(AFN_IMAGE_PASS_OUTPUT_PREFIX + pass))
            throwInvalidArgument("pass '" + name + "' has no output 'passOutput." + pass + "'");
        if (!out.empty() && !outputBound)
            throwInvalidArgument("image '" + name
                + "': denoised passes are made from the denoised beauty; bind 'output' too");
    }
}

std::vector<PassBinding> passBindingsOf(const std::map<std::string, ImageBinding>& images)
{
    std::vector<PassBinding> passes;
    for (const auto& [name, b] : images) {
        const std::string pass = passNameOf(name, AFN_IMAGE_PASS_PREFIX);
        if (pass.empty())
            continue;
        PassBinding p;
        p.name = pass;
        p.light = b.view();
        p.output = images.at(AFN_IMAGE_PASS_OUTPUT_PREFIX + pass).view();
        auto f = images.find(AFN_IMAGE_PASS_FACTOR_PREFIX + pass);
        if (f != images.end())
            p.factor = f->second.view();
        passes.push_back(p);
    }
    return passes;
}

} // namespace afn
