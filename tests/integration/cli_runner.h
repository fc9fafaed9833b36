// SPDX-License-Identifier: Apache-2.0
// Running afntool from tests: exit code, stdout and stderr of one invocation.
#pragma once

#include <string>
#include <vector>

struct CliResult {
    int exitCode = -1;
    std::string out;
    std::string err;
};

/// Run afntool with the given arguments (no shell interpretation of the arguments).
CliResult runAfntool(const std::vector<std::string>& args);

/// A fresh empty directory under the system temp dir, removed by the destructor.
class TempDir {
public:
    TempDir();
    ~TempDir();
    const std::string& path() const { return m_path; }
    std::string file(const std::string& name) const { return m_path + "/" + name; }
    /// Names of all entries (to check that nothing half-written was left behind).
    std::vector<std::string> entries() const;

private:
    std::string m_path;
};
