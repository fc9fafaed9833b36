// SPDX-License-Identifier: Apache-2.0
// Uses the installed C++ wrapper: list the filter types and run one frame through "identity".
#include <afn/afn.hpp>

#include <cstdio>
#include <vector>

int main()
{
    afn::DeviceRef device = afn::newDevice();
    device.commit();
    afn::FilterRef filter = device.newFilter("identity");
    std::vector<float> color(4 * 2 * 3, 0.5f), out(4 * 2 * 3, 0.0f);
    filter.setImage("color", color.data(), afn::Format::Float3, 4, 2);
    filter.setImage("output", out.data(), afn::Format::Float3, 4, 2);
    filter.commit();
    filter.execute();
    std::string message;
    if (device.getError(&message) != afn::Error::None || out[0] != 0.5f) {
        std::fprintf(stderr, "consumer failed: %s\n", message.c_str());
        return 1;
    }
    for (const std::string& t : afn::filterTypes())
        std::printf("%s\n", t.c_str());
    return 0;
}
