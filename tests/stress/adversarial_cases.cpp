// SPDX-License-Identifier: Apache-2.0
#include "adversarial_cases.h"

#include <cfloat>
#include <cmath>
#include <functional>
#include <stdexcept>

namespace stress {

namespace {

/// Deterministic value in [0, 1) for index i (no library code involved).
float unit(std::size_t i, std::uint32_t salt)
{
    std::uint32_t h = static_cast<std::uint32_t>(i) * 0x9E3779B1u ^ salt * 0x85EBCA77u;
    h ^= h >> 15;
    h *= 0x2c1b3c6du;
    h ^= h >> 12;
    return static_cast<float>(h >> 8) / 16777216.0f;
}

using Rewrite = std::function<float(float original, std::size_t index)>;

struct ValueClass {
    const char* name;
    Rewrite rewrite;
};

const std::vector<ValueClass>& genericClasses()
{
    static const std::vector<ValueClass> classes = {
        { "nan-some", [](float v, std::size_t i) { return i % 5 == 0 ? std::nanf("") : v; } },
        { "nan-all", [](float, std::size_t) { return std::nanf(""); } },
        { "inf-some", [](float v, std::size_t i) { return i % 5 == 1 ? INFINITY : v; } },
        { "minus-inf-some", [](float v, std::size_t i) { return i % 5 == 2 ? -INFINITY : v; } },
        { "range-1e30",
            [](float, std::size_t i) {
                // Magnitudes 1e-30..1e30 with both signs, exact +-1e30 included.
                if (i % 11 == 0)
                    return i % 2 ? 1e30f : -1e30f;
                const float mag = std::pow(10.0f, -30.0f + 60.0f * unit(i, 1));
                return unit(i, 2) < 0.5f ? -mag : mag;
            } },
        { "flt-max",
            [](float v, std::size_t i) { return i % 7 == 0 ? (i % 2 ? FLT_MAX : -FLT_MAX) : v; } },
        { "denormal",
            [](float, std::size_t i) {
                const float d = 1.4e-45f + 1.1e-38f * unit(i, 3);
                return i % 3 == 0 ? -d : d;
            } },
        { "zero", [](float, std::size_t i) { return i % 2 ? 0.0f : -0.0f; } },
        { "firefly-1e6", [](float v, std::size_t) { return v; } }, // one pixel: see applyCase
    };
    return classes;
}

/// The value a role-specific class writes, by role and class name.
float roleSpecific(const std::string& role, const std::string& cls, float v, std::size_t i,
    int components, int width)
{
    const int c = static_cast<int>(i % components);
    if (role == "albedo" && cls == "zero-albedo")
        return 0.0f;
    if (role == "albedo" && cls == "black-some") // e.g. emitters and sky beside lit surfaces
        return (i / components) % 5 == 0 ? 0.0f : v;
    if (role == "albedo" && cls == "above-one")
        return 1.0f + 1000.0f * unit(i, 4);
    if (role == "normal" && cls == "zero-length")
        return 0.0f;
    if (role == "normal" && cls == "non-unit")
        return v * std::pow(10.0f, -20.0f + 40.0f * unit(i / 3, 5));
    if (role == "depth" && cls == "zero")
        return 0.0f;
    if (role == "depth" && cls == "negative")
        return -v;
    if (role == "depth" && cls == "sky-1e10")
        return i % 2 ? 1e10f : v;
    if (role == "motion" && cls == "off-screen")
        return (c == 0 ? 3.0f : -3.0f) * static_cast<float>(width);
    if (role == "motion" && cls == "huge")
        return i % 2 ? 1e20f : -1e20f;
    throw std::invalid_argument("unknown case " + role + "/" + cls);
}

const std::vector<AdversarialCase>& specificCases()
{
    static const std::vector<AdversarialCase> cases = {
        { "albedo", "zero-albedo" },
        { "albedo", "black-some" },
        { "albedo", "above-one" },
        { "normal", "zero-length" },
        { "normal", "non-unit" },
        { "depth", "zero" },
        { "depth", "negative" },
        { "depth", "sky-1e10" },
        { "motion", "off-screen" },
        { "motion", "huge" },
    };
    return cases;
}

} // namespace

std::vector<AdversarialCase> adversarialCases()
{
    std::vector<AdversarialCase> cases;
    for (const Role& r : inputRoles())
        for (const ValueClass& v : genericClasses())
            cases.push_back({ r.name, v.name });
    for (const AdversarialCase& c : specificCases())
        cases.push_back(c);
    return cases;
}

void applyCase(const AdversarialCase& c, FrameData& frame)
{
    std::vector<float>& plane = frame.plane(c.role);
    const int comps = role(c.role).channels;
    bool generic = false;
    for (const ValueClass& v : genericClasses())
        if (c.values == v.name) {
            for (std::size_t i = 0; i < plane.size(); ++i)
                plane[i] = v.rewrite(plane[i], i);
            generic = true;
        }
    if (!generic)
        for (std::size_t i = 0; i < plane.size(); ++i)
            plane[i] = roleSpecific(c.role, c.values, plane[i], i, comps, frame.width);
    if (c.values == "firefly-1e6") {
        // One pixel (near the centre) at 1e6 in every channel.
        const std::size_t p
            = static_cast<std::size_t>(frame.height / 2) * frame.width + frame.width / 2;
        for (int k = 0; k < comps; ++k)
            plane[p * comps + k] = 1e6f;
    }
}

} // namespace stress
