// SPDX-License-Identifier: Apache-2.0
// The sample count afntool gives a method with an "spp" parameter (cli/sample_count.h).
#include "sample_count.h"

#include <gtest/gtest.h>

using afntool::sampleCountParam;

TEST(SampleCount, TheFileHeaderUnlessTheUserSetsIt)
{
    const std::map<std::string, std::string> none, user { { "spp", "4" } };
    EXPECT_EQ(sampleCountParam(true, none, 16), std::optional<int>(16)); // from the header
    EXPECT_EQ(sampleCountParam(true, none, std::nullopt), std::optional<int>(0)); // unknown
    EXPECT_FALSE(sampleCountParam(true, user, 16).has_value()); // ":spp=4" is set as given
    EXPECT_FALSE(sampleCountParam(false, none, 16).has_value()); // a method without "spp"
}
