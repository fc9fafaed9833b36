// SPDX-License-Identifier: Apache-2.0
#include "progress.h"

#include <cstdio>
#include <unistd.h>

namespace afntool {

Progress::Progress(int total, bool quiet)
    : m_total(total)
    , m_enabled(!quiet && isatty(2))
{
}

Progress::~Progress()
{
    if (m_drawn)
        std::fprintf(stderr, "\n");
}

void Progress::update(int done, const std::string& label)
{
    if (!m_enabled)
        return;
    const int width = 30;
    const int filled = m_total > 0 ? done * width / m_total : width;
    std::string bar(static_cast<std::size_t>(filled), '#');
    bar.resize(width, '.');
    std::fprintf(stderr, "\r\033[K[%s] %d/%d %s", bar.c_str(), done, m_total, label.c_str());
    std::fflush(stderr);
    m_drawn = true;
}

void Progress::clear()
{
    if (m_drawn) {
        std::fprintf(stderr, "\r\033[K");
        m_drawn = false;
    }
}

void warn(const std::string& message, bool quiet, Progress* progress)
{
    if (quiet)
        return;
    if (progress)
        progress->clear();
    std::fprintf(stderr, "afntool WARNING: %s\n", message.c_str());
}

void note(const std::string& message, bool quiet, Progress* progress)
{
    if (quiet)
        return;
    if (progress)
        progress->clear();
    std::fprintf(stderr, "afntool: %s\n", message.c_str());
}

} // namespace afntool
