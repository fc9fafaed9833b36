// SPDX-License-Identifier: Apache-2.0
#include "cli_runner.h"

#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>

#include <sys/wait.h>
#include <unistd.h>

namespace fs = std::filesystem;

static std::string slurp(const std::string& path)
{
    std::ifstream in(path, std::ios::binary);
    std::ostringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

CliResult runAfntool(const std::vector<std::string>& args)
{
    TempDir io;
    const std::string outPath = io.file("stdout"), errPath = io.file("stderr");
    CliResult r;
    const pid_t pid = fork();
    if (pid == 0) {
        FILE* o = std::freopen(outPath.c_str(), "w", stdout);
        FILE* e = std::freopen(errPath.c_str(), "w", stderr);
        (void)o;
        (void)e;
        std::vector<char*> argv;
        std::string exe = AFNTOOL_PATH;
        argv.push_back(exe.data());
        std::vector<std::string> copy = args;
        for (std::string& a : copy)
            argv.push_back(a.data());
        argv.push_back(nullptr);
        execv(exe.c_str(), argv.data());
        _exit(127);
    }
    int status = 0;
    waitpid(pid, &status, 0);
    r.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    r.out = slurp(outPath);
    r.err = slurp(errPath);
    return r;
}

TempDir::TempDir()
{
    std::random_device rd;
    m_path = (fs::temp_directory_path()
        / ("afn-test-" + std::to_string(getpid()) + "-" + std::to_string(rd())))
                 .string();
    fs::create_directories(m_path);
}

TempDir::~TempDir()
{
    std::error_code ec;
    fs::permissions(m_path, fs::perms::owner_all, fs::perm_options::add, ec);
    fs::remove_all(m_path, ec);
}

std::vector<std::string> TempDir::entries() const
{
    std::vector<std::string> names;
    for (const auto& e : fs::directory_iterator(m_path))
        names.push_back(e.path().filename().string());
    return names;
}
