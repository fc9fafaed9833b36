// SPDX-License-Identifier: Apache-2.0
// Light-path passes by renderer (lib/io/light_passes.cpp) on synthetic files: which layers are
// light passes and which colour factors, the formula text, the recomposition against the beauty,
// the warning when the passes do not add up, and the --aov lights= override.
#include "test_io_util.h"

#include "afn/io.hpp"

#include <cmath>
#include <map>

namespace {

using afn_test::Part;
using afn_test::ScratchDir;
using afn_test::writeExr;

/// A pass's value at (x, y, c): distinct per pass, varying over the image.
float passValue(int index, int x, int y, int c)
{
    return 0.05f * (index + 1) + 0.01f * x + 0.02f * y + 0.03f * c;
}

struct Layer {
    std::string name; ///< layer name ("" = top-level R,G,B)
    bool beauty = false;
};

/// One-part EXR: `layers` hold R,G,B; the beauty layer holds sum(light x factor) (+ `offset`
/// in the left half); every other layer passValue(its index).
void writePassFile(const std::string& path, const std::vector<Layer>& layers,
    const std::vector<std::pair<std::string, std::string>>& terms, float offset = 0.0f)
{
    Part p;
    p.width = 8;
    p.height = 6;
    std::map<std::string, int> index;
    for (std::size_t i = 0; i < layers.size(); ++i) {
        index[layers[i].name] = static_cast<int>(i);
        for (const char* c : { "R", "G", "B" })
            p.channels.push_back(layers[i].name.empty() ? c : layers[i].name + "." + c);
    }
    p.value = [=](int x, int y, int ch) {
        const Layer& l = layers[ch / 3];
        const int c = ch % 3;
        if (!l.beauty)
            return passValue(ch / 3, x, y, c);
        float sum = x < 4 ? offset : 0.0f;
        for (const auto& [light, factor] : terms)
            sum += passValue(index.at(light), x, y, c)
                * (factor.empty() ? 1.0f : passValue(index.at(factor), x, y, c));
        return sum;
    };
    writeExr(path, { p });
}

afn::io::FrameImages readWithPasses(
    const std::string& path, const afn::io::MappingOverrides& overrides = {})
{
    afn::io::ReadOptions ro;
    ro.passes = true;
    ro.overrides = overrides;
    return afn::io::readFrame(path, ro);
}

std::vector<std::string> lightNames(const afn::io::PassRecipe& r)
{
    std::vector<std::string> names;
    for (const afn::io::LightPass& l : r.lights)
        names.push_back(l.name + (l.factor.empty() ? "" : "*" + l.factor));
    return names;
}

const std::vector<std::pair<std::string, std::string>> kBlenderTerms
    = { { "VL.DiffDir", "VL.DiffCol" }, { "VL.DiffInd", "VL.DiffCol" },
          { "VL.GlossDir", "VL.GlossCol" }, { "VL.GlossInd", "VL.GlossCol" }, { "VL.Emit", "" },
          { "VL.Env", "" } };

std::vector<Layer> blenderLayers()
{
    return { { "VL.Combined", true }, { "VL.DiffDir" }, { "VL.DiffInd" }, { "VL.DiffCol" },
        { "VL.GlossDir" }, { "VL.GlossInd" }, { "VL.GlossCol" }, { "VL.Emit" }, { "VL.Env" } };
}

} // namespace

TEST(IoPasses, BlenderCyclesPassesRebuildCombined)
{
    ScratchDir dir;
    const std::string path = dir.file("blender.exr");
    writePassFile(path, blenderLayers(), kBlenderTerms);
    const afn::io::FrameImages f = readWithPasses(path);
    EXPECT_EQ(f.passRecipe.renderer, "blender");
    EXPECT_EQ(lightNames(f.passRecipe),
        (std::vector<std::string> { "DiffDir*DiffCol", "DiffInd*DiffCol", "GlossDir*GlossCol",
            "GlossInd*GlossCol", "Emit", "Env" }));
    ASSERT_EQ(f.passRecipe.factors.size(), 2u);
    EXPECT_EQ(f.passRecipe.factors[0].name, "DiffCol");
    EXPECT_EQ(f.passRecipe.formula,
        "Combined = (DiffDir + DiffInd) x DiffCol + (GlossDir + GlossInd) x GlossCol + Emit + Env");
    EXPECT_EQ(f.passRecipe.lights[0].channels,
        (std::vector<std::string> { "VL.DiffDir.R", "VL.DiffDir.G", "VL.DiffDir.B" }));
    EXPECT_EQ(f.passes.size(), 8u); // 6 lights + 2 factors
    const auto r = afn::io::recompositionOf(f);
    ASSERT_TRUE(r);
    EXPECT_GT(r->psnr, 100.0);
    EXPECT_EQ(afn::io::recompositionWarning(f.passRecipe, *r), "");
}

TEST(IoPasses, PassesThatDoNotAddUpGetAWarningNamingTheError)
{
    ScratchDir dir;
    const std::string path = dir.file("off.exr");
    writePassFile(path, blenderLayers(), kBlenderTerms, 0.5f);
    const afn::io::FrameImages f = readWithPasses(path);
    const auto r = afn::io::recompositionOf(f);
    ASSERT_TRUE(r);
    // Bright pixels clip in the tone map: the linear relative error sees the offset.
    EXPECT_GT(r->relativeRms, afn::io::kRecompositionWarnRelative);
    EXPECT_NEAR(r->maxAbsolute, 0.5, 1e-4);
    const std::string w = afn::io::recompositionWarning(f.passRecipe, *r);
    EXPECT_NE(w.find("do not add up to the beauty: PSNR"), std::string::npos) << w;
    EXPECT_NE(w.find("largest difference 0.5"), std::string::npos) << w;
    EXPECT_NE(w.find("Combined = (DiffDir"), std::string::npos) << w;
}

TEST(IoPasses, AFamilyWrittenInPartIsNamed)
{
    ScratchDir dir;
    const std::string path = dir.file("part.exr");
    writePassFile(path,
        { { "VL.Combined", true }, { "VL.DiffDir" }, { "VL.DiffCol" }, { "VL.Emit" } },
        { { "VL.DiffDir", "VL.DiffCol" }, { "VL.Emit", "" } });
    const afn::io::FrameImages f = readWithPasses(path);
    EXPECT_EQ(lightNames(f.passRecipe), (std::vector<std::string> { "Emit" }));
    EXPECT_EQ(f.passRecipe.missing, (std::vector<std::string> { "DiffInd" }));
    const auto r = afn::io::recompositionOf(f);
    ASSERT_TRUE(r);
    EXPECT_NE(
        afn::io::recompositionWarning(f.passRecipe, *r).find("missing from the formula: DiffInd"),
        std::string::npos);
}

TEST(IoPasses, BlenderLightGroupsWhenThereAreNoLightPasses)
{
    ScratchDir dir;
    const std::string path = dir.file("groups.exr");
    writePassFile(path, { { "VL.Combined", true }, { "VL.Combined_key" }, { "VL.Combined_fill" } },
        { { "VL.Combined_key", "" }, { "VL.Combined_fill", "" } });
    const afn::io::FrameImages f = readWithPasses(path);
    // In the file's channel order (EXR sorts channels by name).
    EXPECT_EQ(
        lightNames(f.passRecipe), (std::vector<std::string> { "Combined_fill", "Combined_key" }));
    EXPECT_GT(afn::io::recompositionOf(f)->psnr, 100.0);
}

TEST(IoPasses, ArnoldAovsWithAndWithoutTheDirectIndirectSplit)
{
    ScratchDir dir;
    const std::string path = dir.file("arnold.exr");
    writePassFile(path,
        { { "", true }, { "diffuse_direct" }, { "diffuse_indirect" }, { "specular" },
            { "transmission_direct" }, { "emission" } },
        { { "diffuse_direct", "" }, { "diffuse_indirect", "" }, { "specular", "" },
            { "transmission_direct", "" }, { "emission", "" } });
    const afn::io::FrameImages f = readWithPasses(path);
    EXPECT_EQ(f.passRecipe.renderer, "arnold");
    EXPECT_EQ(lightNames(f.passRecipe),
        (std::vector<std::string> {
            "diffuse_direct", "diffuse_indirect", "specular", "emission" }));
    EXPECT_EQ(
        f.passRecipe.formula, "RGBA = diffuse_direct + diffuse_indirect + specular + emission");
    // transmission_direct without transmission_indirect: named, and the sum falls short.
    EXPECT_EQ(f.passRecipe.missing, (std::vector<std::string> { "transmission_indirect" }));
    EXPECT_LT(afn::io::recompositionOf(f)->psnr, 60.0);
}

TEST(IoPasses, ArnoldDirectAndIndirectLpes)
{
    ScratchDir dir;
    const std::string path = dir.file("lpe.exr");
    writePassFile(path,
        { { "", true }, { "direct" }, { "indirect" }, { "emission" }, { "background" } },
        { { "direct", "" }, { "indirect", "" }, { "emission", "" }, { "background", "" } });
    const afn::io::FrameImages f = readWithPasses(path);
    EXPECT_EQ(f.passRecipe.renderer, "arnold");
    EXPECT_EQ(f.passRecipe.formula, "RGBA = direct + indirect + emission + background");
    EXPECT_GT(afn::io::recompositionOf(f)->psnr, 100.0);
}

TEST(IoPasses, ArnoldAovsInPartsOfTheirOwnName)
{
    ScratchDir dir;
    const std::string path = dir.file("parts.exr");
    Part beauty, diffuse, specular;
    beauty.name = "rgba";
    diffuse.name = "diffuse";
    specular.name = "specular";
    for (Part* p : { &beauty, &diffuse, &specular })
        p->channels = { "R", "G", "B" };
    diffuse.value = [](int x, int y, int c) { return passValue(1, x, y, c); };
    specular.value = [](int x, int y, int c) { return passValue(2, x, y, c); };
    beauty.value
        = [](int x, int y, int c) { return passValue(1, x, y, c) + passValue(2, x, y, c); };
    writeExr(path, { beauty, diffuse, specular });
    const afn::io::FrameImages f = readWithPasses(path);
    EXPECT_EQ(lightNames(f.passRecipe), (std::vector<std::string> { "diffuse", "specular" }));
    EXPECT_EQ(f.passRecipe.lights[0].subimage, 1);
    EXPECT_GT(afn::io::recompositionOf(f)->psnr, 100.0);
}

TEST(IoPasses, VrayRawLightingTimesTheDiffuseFilter)
{
    ScratchDir dir;
    const std::string path = dir.file("vray.exr");
    writePassFile(path,
        { { "", true }, { "VRayRawLighting" }, { "VRayDiffuseFilter" }, { "VRayReflection" },
            { "VRaySelfIllumination" } },
        { { "VRayRawLighting", "VRayDiffuseFilter" }, { "VRayReflection", "" },
            { "VRaySelfIllumination", "" } });
    const afn::io::FrameImages f = readWithPasses(path);
    EXPECT_EQ(f.passRecipe.renderer, "vray");
    EXPECT_EQ(lightNames(f.passRecipe),
        (std::vector<std::string> {
            "VRayRawLighting*VRayDiffuseFilter", "VRayReflection", "VRaySelfIllumination" }));
    EXPECT_EQ(f.passRecipe.formula,
        "RGB = VRayRawLighting x VRayDiffuseFilter + VRayReflection + VRaySelfIllumination");
    EXPECT_GT(afn::io::recompositionOf(f)->psnr, 100.0);
}

TEST(IoPasses, AovOverrideNamesTheLightsAndTheirFactors)
{
    ScratchDir dir;
    const std::string path = dir.file("custom.exr");
    writePassFile(path, { { "", true }, { "key" }, { "fill" }, { "tint" } },
        { { "key", "tint" }, { "fill", "" } });
    EXPECT_TRUE(readWithPasses(path).passRecipe.empty()); // no renderer names these
    afn::io::MappingOverrides o;
    afn::io::parseOverride("lights=key*tint,fill", o);
    const afn::io::FrameImages f = readWithPasses(path, o);
    EXPECT_EQ(f.passRecipe.renderer, "--aov lights");
    EXPECT_EQ(lightNames(f.passRecipe), (std::vector<std::string> { "key*tint", "fill" }));
    EXPECT_GT(afn::io::recompositionOf(f)->psnr, 100.0);

    afn::io::MappingOverrides none;
    afn::io::parseOverride("lights=none", none);
    ScratchDir dir2;
    const std::string blender = dir2.file("b.exr");
    writePassFile(blender, blenderLayers(), kBlenderTerms);
    EXPECT_TRUE(readWithPasses(blender, none).passRecipe.empty());

    afn::io::MappingOverrides bad;
    afn::io::parseOverride("lights=key,nosuch", bad);
    try {
        readWithPasses(path, bad);
        FAIL() << "a missing layer must be an error";
    } catch (const afn::io::IoError& e) {
        EXPECT_NE(std::string(e.what()).find("no layer 'nosuch'"), std::string::npos) << e.what();
    }
    for (const char* text :
        { "lights=*tint", "lights=key*", "lights=key,,fill", "lights=a**", "lights=a*b*c" }) {
        afn::io::MappingOverrides o2;
        EXPECT_THROW(afn::io::parseOverride(text, o2), afn::io::IoError) << text;
    }
}
