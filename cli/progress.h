// SPDX-License-Identifier: Apache-2.0
// A one-line progress bar on stderr, drawn only when stderr is a terminal.
#pragma once

#include <string>

namespace afntool {

class Progress {
public:
    /// `total` items; disabled when quiet or stderr is not a terminal.
    Progress(int total, bool quiet);
    ~Progress();
    /// Show item `done` of total with a label (e.g. the file being written).
    void update(int done, const std::string& label);
    /// Clear the bar before printing a message, so lines do not interleave.
    void clear();
    bool enabled() const { return m_enabled; }

private:
    int m_total;
    bool m_enabled;
    bool m_drawn = false;
};

/// Print "afntool WARNING: ..." on stderr unless quiet.
void warn(const std::string& message, bool quiet, Progress* progress = nullptr);
/// Print "afntool: <message>" on stderr (a per-frame log line), unless quiet.
void note(const std::string& message, bool quiet, Progress* progress = nullptr);

} // namespace afntool
