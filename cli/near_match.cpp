// SPDX-License-Identifier: Apache-2.0
#include "near_match.h"

#include <algorithm>
#include <cctype>

namespace afntool {

namespace {

std::string lower(std::string s)
{
    for (char& c : s)
        c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return s;
}

/// Optimal string alignment distance (Levenshtein plus transpositions of neighbours).
std::size_t editDistance(const std::string& a, const std::string& b)
{
    const std::size_t n = a.size(), m = b.size();
    std::vector<std::vector<std::size_t>> d(n + 1, std::vector<std::size_t>(m + 1));
    for (std::size_t i = 0; i <= n; ++i)
        d[i][0] = i;
    for (std::size_t j = 0; j <= m; ++j)
        d[0][j] = j;
    for (std::size_t i = 1; i <= n; ++i)
        for (std::size_t j = 1; j <= m; ++j) {
            const std::size_t cost = a[i - 1] == b[j - 1] ? 0 : 1;
            d[i][j] = std::min({ d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + cost });
            if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1])
                d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
        }
    return d[n][m];
}

} // namespace

std::string nearMatch(const std::string& given, const std::vector<std::string>& candidates)
{
    const std::string g = lower(given);
    // Letters only count for the length limit: "--ab" is as short as "ab".
    const std::size_t letters = static_cast<std::size_t>(std::count_if(
        g.begin(), g.end(), [](char c) { return std::isalnum(static_cast<unsigned char>(c)); }));
    const std::size_t limit = letters <= 4 ? 1 : 2;
    std::string best;
    std::size_t bestDistance = limit + 1;
    for (const std::string& c : candidates) {
        if (c.empty() || c == given)
            continue;
        const std::string l = lower(c);
        std::size_t d = editDistance(g, l);
        if (d > limit && letters >= 4 && l.size() > g.size() && l.compare(0, g.size(), g) == 0)
            d = limit; // a prefix of the name
        if (d < bestDistance) {
            bestDistance = d;
            best = c;
        }
    }
    return best;
}

std::string didYouMean(const std::string& given, const std::vector<std::string>& candidates)
{
    const std::string m = nearMatch(given, candidates);
    return m.empty() ? std::string() : " (did you mean '" + m + "'?)";
}

std::string joinNames(const std::vector<std::string>& names)
{
    std::string out;
    for (std::size_t i = 0; i < names.size(); ++i)
        out += (i ? ", " : "") + names[i];
    return out;
}

} // namespace afntool
