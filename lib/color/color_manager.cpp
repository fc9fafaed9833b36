// SPDX-License-Identifier: Apache-2.0
// ColorManager: a loaded OpenColorIO config and a cache of CPU processors.
#include "afn/color.hpp"

#include <OpenColorIO/OpenColorIO.h>
#include <sys/stat.h>

#include <map>
#include <mutex>

namespace OCIO = OCIO_NAMESPACE;

namespace afn::color {
namespace {

std::string joinNames(const std::vector<std::string>& names)
{
    std::string out;
    for (const auto& n : names)
        out += (out.empty() ? "" : ", ") + ("'" + n + "'");
    return out;
}

bool contains(const std::vector<std::string>& names, const std::string& name)
{
    for (const auto& n : names)
        if (n == name)
            return true;
    return false;
}

} // namespace

struct ColorManager::Impl {
    ConfigChoice choice;
    OCIO::ConstConfigRcPtr config;
    mutable std::mutex mutex;
    mutable std::map<std::string, OCIO::ConstCPUProcessorRcPtr> cache;

    // Fetch or build a CPU processor; `build` runs under the lock (OCIO processor creation is
    // thread-safe, but building once per key keeps the cache simple).
    template <class Build>
    OCIO::ConstCPUProcessorRcPtr processor(const std::string& key, Build build) const
    {
        std::lock_guard<std::mutex> lock(mutex);
        auto it = cache.find(key);
        if (it != cache.end())
            return it->second;
        try {
            OCIO::ConstCPUProcessorRcPtr cpu = build();
            cache.emplace(key, cpu);
            return cpu;
        } catch (const OCIO::Exception& e) {
            throw ColorError(std::string("OpenColorIO: cannot build the transform: ") + e.what()
                + " (" + choice.path + ")");
        }
    }

    void apply(const OCIO::ConstCPUProcessorRcPtr& cpu, float* pixels, int width, int height,
        int stride) const
    {
        if (cpu->isNoOp())
            return;
        const ptrdiff_t fs = sizeof(float);
        OCIO::PackedImageDesc desc(pixels, width, height, 3, OCIO::BIT_DEPTH_F32, fs, fs * stride,
            fs * stride * static_cast<ptrdiff_t>(width));
        try {
            cpu->apply(desc);
        } catch (const OCIO::Exception& e) {
            throw ColorError(std::string("OpenColorIO: ") + e.what());
        }
    }

    void requireSpace(const std::string& name, const char* what, const ColorManager& cm) const
    {
        if (!config->getColorSpace(name.c_str()))
            throw ColorError(std::string("unknown ") + what + " colour space '" + name + "' in "
                + choice.path + "; valid: " + joinNames(cm.colorSpaces()));
    }
};

ColorManager::ColorManager(const std::string& explicitPath)
    : m_impl(std::make_unique<Impl>())
{
    m_impl->choice = resolveConfig(explicitPath);
    const std::string& path = m_impl->choice.path;
    const std::string from = " (" + path + ", from " + m_impl->choice.reason + ")";
    struct stat st { };
    if (::stat(path.c_str(), &st) != 0)
        throw ColorError("colour config not found" + from);
    if (!S_ISREG(st.st_mode))
        throw ColorError("colour config is not a regular file" + from);
    try {
        OCIO::ConstConfigRcPtr config = OCIO::Config::CreateFromFile(path.c_str());
        config->validate();
        m_impl->config = config;
    } catch (const OCIO::Exception& e) {
        throw ColorError(std::string("invalid colour config: ") + e.what() + from);
    }
    if (m_impl->config->getNumDisplays() == 0)
        throw ColorError("colour config defines no display" + from);
}

ColorManager::~ColorManager() = default;

const ConfigChoice& ColorManager::config() const
{
    return m_impl->choice;
}

std::string ColorManager::workingSpace() const
{
    OCIO::ConstColorSpaceRcPtr cs = m_impl->config->getColorSpace(OCIO::ROLE_SCENE_LINEAR);
    if (!cs)
        throw ColorError("colour config has no scene_linear role (" + m_impl->choice.path + ")");
    return cs->getName();
}

std::vector<std::string> ColorManager::colorSpaces() const
{
    std::vector<std::string> names;
    const auto& cfg = m_impl->config;
    const int n = cfg->getNumColorSpaces(OCIO::SEARCH_REFERENCE_SPACE_ALL, OCIO::COLORSPACE_ALL);
    for (int i = 0; i < n; ++i)
        names.emplace_back(cfg->getColorSpaceNameByIndex(
            OCIO::SEARCH_REFERENCE_SPACE_ALL, OCIO::COLORSPACE_ALL, i));
    return names;
}

std::vector<std::string> ColorManager::displays() const
{
    std::vector<std::string> names;
    for (int i = 0; i < m_impl->config->getNumDisplays(); ++i)
        names.emplace_back(m_impl->config->getDisplay(i));
    return names;
}

std::vector<std::string> ColorManager::views(const std::string& display) const
{
    if (!contains(displays(), display))
        throw ColorError("unknown display '" + display + "' in " + m_impl->choice.path
            + "; valid: " + joinNames(displays()));
    std::vector<std::string> names;
    for (int i = 0; i < m_impl->config->getNumViews(display.c_str()); ++i)
        names.emplace_back(m_impl->config->getView(display.c_str(), i));
    return names;
}

std::string ColorManager::defaultDisplay() const
{
    return m_impl->config->getDefaultDisplay();
}

std::string ColorManager::defaultView(const std::string& display) const
{
    const std::string d = display.empty() ? defaultDisplay() : display;
    views(d); // validates the display name
    return m_impl->config->getDefaultView(d.c_str());
}

bool ColorManager::hasColorSpace(const std::string& name) const
{
    return !name.empty() && m_impl->config->getColorSpace(name.c_str()) != nullptr;
}

std::string ColorManager::canonicalName(const std::string& name) const
{
    OCIO::ConstColorSpaceRcPtr cs
        = name.empty() ? nullptr : m_impl->config->getColorSpace(name.c_str());
    return cs ? cs->getName() : std::string();
}

std::vector<std::string> ColorManager::aliases(const std::string& name) const
{
    std::vector<std::string> out;
    OCIO::ConstColorSpaceRcPtr cs
        = name.empty() ? nullptr : m_impl->config->getColorSpace(name.c_str());
    for (std::size_t i = 0; cs && i < cs->getNumAliases(); ++i)
        out.emplace_back(cs->getAlias(i));
    return out;
}

static void checkBuffer(const float* pixels, int width, int height, int stride)
{
    if (width < 0 || height < 0)
        throw ColorError("colour conversion: negative image size");
    if (stride < 3)
        throw ColorError("colour conversion: pixel stride " + std::to_string(stride) + " < 3");
    if (!pixels && width > 0 && height > 0)
        throw ColorError("colour conversion: null pixel buffer");
}

void ColorManager::convert(float* pixels, int width, int height, int stride,
    const std::string& from, const std::string& to) const
{
    checkBuffer(pixels, width, height, stride);
    m_impl->requireSpace(from, "source", *this);
    m_impl->requireSpace(to, "destination", *this);
    if (width == 0 || height == 0)
        return;
    // LOSSLESS: these conversions feed the denoiser, so no fast log/exp approximations here.
    auto cpu = m_impl->processor("cs\x1f" + from + "\x1f" + to, [&] {
        return m_impl->config->getProcessor(from.c_str(), to.c_str())
            ->getOptimizedCPUProcessor(
                OCIO::BIT_DEPTH_F32, OCIO::BIT_DEPTH_F32, OCIO::OPTIMIZATION_LOSSLESS);
    });
    m_impl->apply(cpu, pixels, width, height, stride);
}

void ColorManager::toWorking(
    float* pixels, int width, int height, int stride, const std::string& from) const
{
    if (from.empty())
        return;
    convert(pixels, width, height, stride, from, workingSpace());
}

void ColorManager::toDisplay(float* pixels, int width, int height, int stride,
    const std::string& from, const std::string& display, const std::string& view) const
{
    checkBuffer(pixels, width, height, stride);
    const std::string src = from.empty() ? workingSpace() : from;
    m_impl->requireSpace(src, "source", *this);
    const std::string d = display.empty() ? defaultDisplay() : display;
    const std::vector<std::string> viewNames = views(d); // throws on an unknown display
    const std::string v = view.empty() ? defaultView(d) : view;
    if (!contains(viewNames, v))
        throw ColorError("unknown view '" + v + "' for display '" + d + "' in "
            + m_impl->choice.path + "; valid: " + joinNames(viewNames));
    if (width == 0 || height == 0)
        return;
    // Previews only: the default optimisation (fast log/exp, ~1e-4 error) is fine here.
    auto cpu = m_impl->processor("dv\x1f" + src + "\x1f" + d + "\x1f" + v, [&] {
        auto dvt = OCIO::DisplayViewTransform::Create();
        dvt->setSrc(src.c_str());
        dvt->setDisplay(d.c_str());
        dvt->setView(v.c_str());
        return m_impl->config->getProcessor(dvt)->getDefaultCPUProcessor();
    });
    m_impl->apply(cpu, pixels, width, height, stride);
}

} // namespace afn::color
