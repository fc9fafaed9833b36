// SPDX-License-Identifier: Apache-2.0
// The afn method's own parameters (besides the shared aux/spp, quality and skip ones).
//
// taa: temporal anti-aliasing of the remodulated output (stages/taa.h, the last step of SVGF and
// BMFR; not in the AFN paper): each frame's output is blended with the previous output,
// reprojected and clamped in YCoCg to the current frame's 3x3 neighbourhood.
//   auto (default)  on when the model that runs the frame was trained below 16 spp (the 1-spp
//                   models), off for the 16- and 64-spp models
//   off, on         as named
// Why auto: on the held-out set (docs/afn-evaluation.md, output TAA) the TAA raised
// afn's 1-spp mean PSNR (+0.20 dB with the blend factor 0.7) and SSIM and cut the temporal error,
// but at 16 spp it lost PSNR on 4 of 6 sequences (0.32 dB on average, up to 1.3): a sharp 16-spp
// result has little flicker left to remove and the clamp box blurs it.
// The blend factor 0.7 is the best mean PSNR of 0.35 / 0.5 / 0.7 / 0.85 on the rendered
// training sequences (1 spp, their leave-one-out references), not on the held-out set.
// Under work skipping the network computes the rows within kTaaWorkMargin of the needed ones
// (afn_method.cpp), as bmfr does.
//
// postFilter: the edge-aware a-trous smoothing of the final output (post_filter.h; not in the AFN
// paper), guided by albedo, normal and depth, against the low-frequency blotches.
//   auto (default)  on for the models trained below 16 spp, off for the 16- and 64-spp ones
//   off, on         as named
// Why auto: on the rendered training sequences it raised the mean PSNR at 1 spp (+0.3 dB) and
// lowered it slightly at 16 and 64 spp (docs/afn-evaluation.md, post-filter, with the
// held-out results).
// Under work skipping the network then computes kPostFilterRadius more rows around the needed
// ones.
//
// alphaMinHighSpp: the temporal accumulation's minimum blend (the shared stage's alphaMin) when
// the model that runs the frame was trained at 4 spp or more; alphaMin applies below (the 1-spp
// models).
// Why 0.5, not BMFR's 0.2: above 1 spp the accumulated input's error is less its noise than what
// its history adds (the blur of a bilinear resampling each frame under a moving camera, lag);
// a shorter history keeps it sharper. Chosen on training sequences (two per family, frames 0-5):
// at 16 spp 0.2 / 0.35 / 0.5 / 0.7 gave 30.763 / 30.784 / 30.818 / 30.822 dB with the temporal
// error 0.0258 / 0.0258 / 0.0258 / 0.0260; at 4 spp 0.2 / 0.35 / 0.5 gave 29.731 / 29.773 /
// 29.846 dB, 0.02689 / 0.02686 / 0.02684. 0.5 is the best PSNR at an unchanged temporal error.
// The held-out results: docs/afn-evaluation.md, "The 16-spp model's history" and "Other sample
// counts".
//
// precision: the arithmetic of the network's convolutions (nn::Conv, cpu/conv_avx512_bf16.cpp).
//   auto (default)  bf16 where the CPU has AMX-BF16 (tiles of 16 pixels x 16 channels,
//                   cpu/conv_amx_bf16.cpp) or AVX512_BF16 (VDPBF16PS: twice fp32's multiply-adds
//                   per instruction), fp32 elsewhere
//   fp32            as named
//   bf16            bf16 operands, fp32 sums, on every CPU with AVX-512 (emulated with AVX-512F
//                   FMAs where AVX512_BF16 is missing: the same results, fp32's speed); refused
//                   without the AVX-512 engine
// Why auto: on the held-out set bf16 is within 0.035 dB of fp32 for every model
// (docs/afn-evaluation.md, "fp32 and bf16"); the filtering, fusion and the output stages stay
// fp32.
#pragma once

#include "base/params.h"
#include "stages/highlight_bypass.h"

namespace afn::afnet {

struct Settings {
    enum class Taa { Auto, Off, On };
    Taa taa = Taa::Auto; ///< temporal anti-aliasing of the output (stages/taa.h)
    float taaAlpha = 0.7f; ///< TAA weight of the current frame
    enum class PostFilter { Auto, Off, On };
    PostFilter postFilter
        = PostFilter::Auto; ///< edge-aware smoothing of the output (post_filter.h)
    enum class Precision { Auto, Fp32, Bf16 };
    Precision precision = Precision::Auto; ///< the network's convolutions (see above)
    /// Factor of the highlight bypass's limit over the frame's bright level, 0 = off
    /// (stages/highlight_bypass.h).
    float highlights = kHighlightFactor;
    /// The accumulation's alphaMin for the models trained at kAlphaMinHighSppFrom spp or more.
    float alphaMinHighSpp = 0.5f;
};

/// Models trained at this many samples per pixel or more accumulate with alphaMinHighSpp.
constexpr int kAlphaMinHighSppFrom = 4;

/// The accumulation's minimum blend for a model trained at `modelSpp`: `alphaMin` (the shared
/// parameter) below kAlphaMinHighSppFrom, else Settings::alphaMinHighSpp; the CPU and the CUDA
/// filter both ask here.
inline float accumulationAlphaMin(const Settings& s, float alphaMin, int modelSpp)
{
    return modelSpp >= kAlphaMinHighSppFrom ? s.alphaMinHighSpp : alphaMin;
}

/// Models trained at this many samples per pixel or more run without the post-filter under
/// postFilter=auto.
constexpr int kPostFilterAutoMaxSppExclusive = 16;

/// Models trained at this many samples per pixel or more run without TAA under taa=auto.
constexpr int kTaaAutoMaxSppExclusive = 16;

/// Whether the output TAA runs for a model trained at `modelSpp` (on, or auto below
/// kTaaAutoMaxSppExclusive); the CPU and the CUDA filter both ask here.
inline bool taaOn(const Settings& s, int modelSpp)
{
    return s.taa == Settings::Taa::On
        || (s.taa == Settings::Taa::Auto && modelSpp < kTaaAutoMaxSppExclusive);
}

/// Whether the post-filter runs for a model trained at `modelSpp` (on, or auto below
/// kPostFilterAutoMaxSppExclusive).
inline bool postFilterOn(const Settings& s, int modelSpp)
{
    return s.postFilter == Settings::PostFilter::On
        || (s.postFilter == Settings::PostFilter::Auto
            && modelSpp < kPostFilterAutoMaxSppExclusive);
}

/// The descriptors of Settings (settings.cpp).
const ParamBinding<Settings>& settingsBinding();

} // namespace afn::afnet
