// SPDX-License-Identifier: Apache-2.0
// Progress of a run on stderr: a one-line bar when stderr is a terminal, one plain line per item
// otherwise (farm logs, pipes), and a summary line at the end (items, time, rate). Nothing with
// --quiet.
#pragma once

#include <chrono>
#include <string>

namespace afntool {

class Progress {
public:
    /// `total` items; silent when quiet. The bar is drawn only when stderr is a terminal.
    Progress(int total, bool quiet);
    ~Progress();
    /// Item `done` (0-based) of total is starting, with a label (e.g. the file being read), so
    /// items before it are finished; done == total: all are. Without a terminal, one line per
    /// finished item with its wall time ("afntool: [3/60] shot.0002.exr 0.41 s"; none for a
    /// single item).
    void update(int done, const std::string& label);
    /// A figure of the item in progress, printed after its time on its line ("..., history cut
    /// 12 %"; not on the bar); a later call replaces it.
    void annotate(const std::string& detail);
    /// Clear the bar before printing a message, so lines do not interleave.
    void clear();
    /// Print the summary line, "afntool: 8 frames in 3.21 s (2.49 fps)".
    void finish();
    bool enabled() const { return m_bar; }

private:
    int m_total;
    bool m_quiet;
    bool m_bar; ///< stderr is a terminal: one redrawn line
    bool m_drawn = false;
    std::string m_label; ///< label of the item in progress (plain lines)
    std::string m_detail; ///< annotate()'s figures of the item in progress
    std::chrono::steady_clock::time_point m_start;
    std::chrono::steady_clock::time_point m_itemStart; ///< when the item in progress started
};

/// "8 frames in 3.21 s (2.49 fps)"; the rate is omitted when no time was measured.
std::string summaryText(int frames, double seconds);

/// Print "afntool WARNING: ..." on stderr unless quiet.
void warn(const std::string& message, bool quiet, Progress* progress = nullptr);
/// Print "afntool: <message>" on stderr (a log line), unless quiet.
void note(const std::string& message, bool quiet, Progress* progress = nullptr);

} // namespace afntool
