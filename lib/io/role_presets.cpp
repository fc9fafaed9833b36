// SPDX-License-Identifier: Apache-2.0
// Renderer naming conventions as data: which layers hold which role, and their space tags.
//
// Facts come from the project's reference notes (Blender Cycles 3.4 verified by rendering; the
// others from vendor documentation). Where the notes mark a convention UNVERIFIED, the choice made
// here is written next to it; users correct it with --aov tag overrides (e.g. motion.yUp=false).
#include "io_internal.h"

namespace afn::io::detail {
namespace {

using Comps = std::vector<std::vector<std::string>>;
using Tags = std::vector<std::pair<std::string, std::string>>;

const Comps kRgb = { { "R", "G", "B" }, { "r", "g", "b" }, { "red", "green", "blue" } };
const Comps kXyz = { { "X", "Y", "Z" }, { "x", "y", "z" }, { "R", "G", "B" } };
const Comps kRgbOrXyz
    = { { "R", "G", "B" }, { "X", "Y", "Z" }, { "r", "g", "b" }, { "red", "green", "blue" } };
const Comps kOne = { { "Z" }, { "R" }, { "Y" }, { "V" }, { "X" }, { "z" } };
const Comps kTwo = { { "X", "Y" }, { "R", "G" }, { "x", "y" }, { "U", "V" }, { "r", "g" } };
const Comps kAlpha = { { "A" }, { "a" } };

Candidate cand(std::string layer, const Comps& comps, Tags tags = {})
{
    return Candidate { std::move(layer), comps, std::move(tags), false };
}
Candidate generic(std::string layer, const Comps& comps)
{
    return Candidate { std::move(layer), comps, {}, true };
}

SpaceTag tag(const char* normal, const char* depth, const char* dir, bool yUp)
{
    SpaceTag t;
    t.normalSpace = normal;
    t.depthKind = depth;
    t.motionDirection = dir;
    t.motionYUp = yUp;
    t.motionUnits = "pixels";
    return t;
}

std::vector<Preset> buildPresets()
{
    std::vector<Preset> p;
    // Blender Cycles 3.4 (verified): layers are "<view layer>.<pass>" and matched by suffix.
    // "Noisy Image" (written when the built-in denoiser ran, so Combined is denoised) is preferred.
    p.push_back({ "blender", "Blender Cycles", { "blendermultichannel", "cycles." },
        tag("world", "planar", "to-previous", true),
        {
            // Top-level R,G,B last: afntool's own output keeps Blender AOV layers beside it.
            { Role::Color,
                { cand("Noisy Image", kRgb), cand("Combined", kRgb), generic("", kRgb) } },
            { Role::Albedo, { cand("Denoising Albedo", kRgb), cand("DiffCol", kRgb) } },
            { Role::Normal,
                { cand("Normal", kXyz, { { "normal.space", "world" } }),
                    cand("Denoising Normal", kXyz, { { "normal.space", "camera" } }) } },
            { Role::Depth,
                { cand("Depth", kOne, { { "depth.kind", "planar" } }),
                    cand("Denoising Depth", kOne, { { "depth.kind", "radial" } }) } },
            { Role::Position, { cand("Position", kXyz) } },
            // X,Y = pos(t-1) - pos(t) in pixels, y up; Z,W (negated forward) unused.
            { Role::Motion, { cand("Vector", { { "X", "Y" } }) } },
            { Role::Alpha,
                { cand("Combined", kAlpha), cand("Noisy Image", kAlpha), generic("", kAlpha) } },
            { Role::Variance, { cand("Denoising Variance", kRgb) } },
        } });
    // Arnold: beauty R,G,B,A (or RGBA.* from USD), N and P world, Z planar. motionvector direction
    // and y sign are UNVERIFIED: chosen as time0 -> time1 (shutter open to close, i.e. to-next),
    // raw pixels, y up (Nuke/RE:Vision convention).
    p.push_back({ "arnold", "Arnold", { "arnold/", "arnold" },
        tag("world", "planar", "to-next", true),
        {
            { Role::Color, { generic("", kRgb), cand("RGBA", kRgb) } },
            { Role::Albedo,
                { cand("denoise_albedo", kRgb), cand("diffuse_albedo", kRgb), cand("albedo", kRgb),
                    cand("diffuse_albedo_noice", kRgb) } },
            { Role::Normal, { cand("N", kXyz), cand("N_noice", kXyz) } },
            { Role::Depth, { generic("", { { "Z" } }), cand("Z", kOne), cand("Z_noice", kOne) } },
            { Role::Position, { cand("P", kXyz) } },
            { Role::Motion, { cand("motionvector", kTwo) } },
            { Role::Alpha, { generic("", kAlpha), cand("RGBA", kAlpha) } },
            { Role::Variance, { cand("variance", kRgb) } },
            { Role::Specular, { cand("specular", kRgb) } },
        } });
    // RenderMan denoiser AOVs. normal (Nn) is taken as camera space with +Z into the scene
    // (RenderMan's left-handed "current" space); forward/backward are raster pixels, y down.
    // Both UNVERIFIED.
    p.push_back({ "renderman", "RenderMan", { "renderman", "prman" },
        tag("camera", "planar", "to-previous", false),
        {
            { Role::Color, { cand("Ci", kRgb), cand("beauty", kRgb), generic("", kRgb) } },
            { Role::Albedo, { cand("albedo", kRgb) } },
            { Role::Normal, { cand("normal", kXyz) } },
            { Role::Depth, { cand("zfiltered", kOne), cand("z", kOne) } },
            { Role::Position, { cand("P", kXyz) } },
            { Role::Motion,
                { cand("backward", kTwo, { { "motion.direction", "to-previous" } }),
                    cand("forward", kTwo, { { "motion.direction", "to-next" } }) } },
            { Role::Alpha,
                { cand("a", kOne), cand("Ci", kAlpha), cand("beauty", kAlpha),
                    generic("", kAlpha) } },
            { Role::Variance, { cand("mse", kRgb) } },
            { Role::Specular, { cand("specular", kRgb) } },
        } });
    // V-Ray render elements: normals in camera space with +Z toward the viewer; velocity points to
    // the next frame (docs). Velocity y sign UNVERIFIED: chosen y up. zDepth may be normalised.
    p.push_back(
        { "vray", "V-Ray", { "vray" }, tag("camera-toward-viewer", "planar", "to-next", true),
            {
                { Role::Color, { generic("", kRgb) } },
                { Role::Albedo, { cand("diffuse", kRgb), cand("DiffuseFilter", kRgb) } },
                { Role::Normal, { cand("normals", kXyz) } },
                { Role::Depth, { cand("zDepth", kOne), cand("ZDepth", kOne) } },
                { Role::Motion, { cand("velocity", kTwo) } },
                { Role::Alpha, { generic("", kAlpha) } },
                { Role::Variance, { cand("noiseLevel", kOne) } },
                { Role::Specular, { cand("specular", kRgb) } },
            } });
    // Redshift: N and P world, Z planar. MotionVectors direction/sign UNVERIFIED: chosen to-next,
    // pixels, y up.
    p.push_back(
        { "redshift", "Redshift", { "redshift", "rs/" }, tag("world", "planar", "to-next", true),
            {
                { Role::Color, { generic("", kRgb) } },
                { Role::Albedo, { cand("DiffuseFilter", kRgb) } },
                { Role::Normal, { cand("N", kXyz) } },
                { Role::Depth, { generic("", { { "Z" } }), cand("Z", kOne) } },
                { Role::Position, { cand("P", kXyz) } },
                { Role::Motion, { cand("MotionVectors", kTwo) } },
                { Role::Alpha, { generic("", kAlpha) } },
            } });
    // Houdini Karma: beauty C (or R,G,B,A). Spaces and motion UNVERIFIED: N world, depth planar
    // (ray:hitPz), motionvector to-next in pixels, y up.
    p.push_back({ "karma", "Karma", { "karma" }, tag("world", "planar", "to-next", true),
        {
            { Role::Color, { cand("C", kRgb), generic("", kRgb) } },
            { Role::Albedo, { cand("albedo", kRgb) } },
            { Role::Normal, { cand("N", kXyz) } },
            { Role::Depth, { cand("depth", kOne), cand("Pz", kOne) } },
            { Role::Position, { cand("P", kXyz) } },
            { Role::Motion, { cand("motionvector", kTwo) } },
            { Role::Alpha, { cand("C", kAlpha), generic("", kAlpha) } },
        } });
    // Anything else: top-level R,G,B[,A] and Z, plus common layer names.
    p.push_back({ "generic", "generic", {}, tag("world", "planar", "to-previous", false),
        {
            { Role::Color, { generic("", kRgb), generic("rgba", kRgb), generic("RGBA", kRgb) } },
            { Role::Albedo, { generic("albedo", kRgb), generic("diffuse_albedo", kRgb) } },
            { Role::Normal, { generic("N", kRgbOrXyz), generic("normal", kRgbOrXyz) } },
            { Role::Depth,
                { generic("", { { "Z" } }), generic("depth", kOne), generic("Z", kOne) } },
            { Role::Position, { generic("P", kXyz), generic("position", kXyz) } },
            { Role::Motion, { generic("motion", kTwo), generic("motionvector", kTwo) } },
            { Role::Alpha, { generic("", kAlpha), generic("rgba", kAlpha) } },
        } });
    return p;
}

} // namespace

const std::vector<Preset>& presets()
{
    static const std::vector<Preset> table = buildPresets();
    return table;
}

} // namespace afn::io::detail
