// SPDX-License-Identifier: Apache-2.0
#include "progress.h"

#include <cstdio>
#include <unistd.h>

namespace afntool {

Progress::Progress(int total, bool quiet)
    : m_total(total)
    , m_quiet(quiet)
    , m_bar(!quiet && isatty(2))
    , m_start(std::chrono::steady_clock::now())
    , m_itemStart(m_start)
{
}

Progress::~Progress()
{
    if (m_drawn)
        std::fprintf(stderr, "\n");
}

void Progress::update(int done, const std::string& label)
{
    if (m_quiet)
        return;
    if (!m_bar) {
        // One line per finished item with its time, so that a log that is not a terminal still
        // shows where a run is (an error in the first item comes first); a single item only gets
        // the summary.
        const auto now = std::chrono::steady_clock::now();
        if (done > 0 && m_total > 1)
            std::fprintf(stderr, "afntool: [%d/%d] %s %.2f s%s\n", done, m_total, m_label.c_str(),
                std::chrono::duration<double>(now - m_itemStart).count(), m_detail.c_str());
        m_label = label;
        m_detail.clear();
        m_itemStart = now;
        return;
    }
    const int width = 30;
    const int filled = m_total > 0 ? done * width / m_total : width;
    std::string bar(static_cast<std::size_t>(filled), '#');
    bar.resize(width, '.');
    std::fprintf(stderr, "\r\033[K[%s] %d/%d %s", bar.c_str(), done, m_total, label.c_str());
    std::fflush(stderr);
    m_drawn = true;
}

void Progress::annotate(const std::string& detail)
{
    m_detail = ", " + detail; // the item's latest (a benchmark item runs several frames)
}

void Progress::clear()
{
    if (m_drawn) {
        std::fprintf(stderr, "\r\033[K");
        m_drawn = false;
    }
}

void Progress::finish()
{
    clear();
    if (m_quiet)
        return;
    const double seconds
        = std::chrono::duration<double>(std::chrono::steady_clock::now() - m_start).count();
    std::fprintf(stderr, "afntool: %s\n", summaryText(m_total, seconds).c_str());
}

std::string summaryText(int frames, double seconds)
{
    char text[128];
    if (seconds > 0.0)
        std::snprintf(text, sizeof text, "%d frame%s in %.2f s (%.2f fps)", frames,
            frames == 1 ? "" : "s", seconds, frames / seconds);
    else
        std::snprintf(
            text, sizeof text, "%d frame%s in %.2f s", frames, frames == 1 ? "" : "s", seconds);
    return text;
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
