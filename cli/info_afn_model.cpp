// SPDX-License-Identifier: Apache-2.0
#include "info_afn_model.h"

#include "cli_error.h"

#include "afn/afn.hpp"

#include <vector>

namespace afntool {

namespace {

afn::Format formatOf(int components)
{
    return components == 1 ? afn::Format::Float
        : components == 2  ? afn::Format::Float2
        : components == 3  ? afn::Format::Float3
                           : afn::Format::Float4;
}

} // namespace

std::string afnModelFor(
    const Options& opts, const afn::io::FrameImages& frame, std::string* network)
{
    using afn::io::Role;
    afn::DeviceRef device = afn::newDevice(afn::DeviceType::CPU);
    if (!device)
        throw CliError("cannot create an afn device");
    device.commit();
    afn::FilterRef filter = device.newFilter("afn");
    std::string message;
    if (!opts.weights.empty()) {
        std::vector<char> data;
        if (!afn::readFile(opts.weights, data))
            throw CliError("cannot read the weights file", opts.weights);
        filter.setData(AFN_DATA_WEIGHTS, data.data(), data.size());
        if (device.getError(&message) != afn::Error::None)
            return "error: " + message;
    }
    // The roles are bound as a --denoise would bind them; nothing is executed.
    const std::pair<Role, const char*> roles[]
        = { { Role::Color, AFN_IMAGE_COLOR }, { Role::Albedo, AFN_IMAGE_ALBEDO },
              { Role::Normal, AFN_IMAGE_NORMAL }, { Role::Depth, AFN_IMAGE_DEPTH },
              { Role::Position, AFN_IMAGE_POSITION }, { Role::Motion, AFN_IMAGE_MOTION } };
    int width = 0, height = 0;
    for (const auto& [role, name] : roles) {
        auto it = frame.roles.find(role);
        if (it == frame.roles.end())
            continue;
        const afn::io::RoleImage& r = it->second;
        filter.setImage(name, const_cast<float*>(r.pixels.data()), formatOf(r.components), r.width,
            r.height, 0, r.components * sizeof(float), 0);
        width = r.width;
        height = r.height;
    }
    if (frame.camera) {
        filter.setFloats(AFN_ARRAY_VIEW_PROJECTION, frame.camera->viewProjection, 16);
        filter.setFloats(AFN_ARRAY_PIXEL_OFFSET, frame.camera->pixelOffset, 2);
    }
    if (frame.samples) // the model trained nearest the file's sample count, as --denoise runs
        filter.set(AFN_PARAM_SPP, *frame.samples);
    std::vector<float> output(static_cast<std::size_t>(width) * height * 3);
    filter.setImage(AFN_IMAGE_OUTPUT, output.data(), afn::Format::Float3, width, height);
    filter.commit();
    if (device.getError(&message) != afn::Error::None)
        return "error: " + message;
    if (network)
        *network = networkArithmetic(filter);
    return filter.get<std::string>(AFN_STAT_AFN_MODEL);
}

std::string networkArithmetic(const afn::FilterRef& filter)
{
    if (filter.get<int>(AFN_STAT_AFN_PRECISION) != 16)
        return "fp32";
    if (filter.get<bool>(AFN_STAT_AFN_BF16_AMX))
        return "bf16 (AMX)";
    return filter.get<bool>(AFN_STAT_AFN_BF16_HARDWARE) ? "bf16 (AVX512_BF16)" : "bf16 (emulated)";
}

} // namespace afntool
