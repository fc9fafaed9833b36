// SPDX-License-Identifier: Apache-2.0
#include "methods/afn/settings.h"

namespace afn::afnet {

const ParamBinding<Settings>& settingsBinding()
{
    using S = Settings;
    using T = Settings::Taa;
    using P = Settings::PostFilter;
    using R = Settings::Precision;
    static const ParamBinding<S> binding
        = ParamBinding<S>()
              .add(&S::taa, "taa", { { "auto", T::Auto }, { "off", T::Off }, { "on", T::On } },
                  "TAA",
                  "temporal anti-aliasing of the output (as svgf's taa: history clamped to the "
                  "current frame's 3x3 neighbourhood in YCoCg, then blended); auto: on for the "
                  "models trained below 16 spp, off for the 16- and 64-spp ones; under work "
                  "skipping the network then also computes 3 rows around the needed ones")
              .add(&S::taaAlpha, "taaAlpha", 0.0, 1.0, "TAA blend factor",
                  "weight of the current frame in the TAA blend (0.7, chosen on training "
                  "sequences; svgf and BMFR use 0.2)")
              .add(&S::postFilter, "postFilter",
                  { { "auto", P::Auto }, { "off", P::Off }, { "on", P::On } }, "post-filter",
                  "edge-aware smoothing of the output (3 a-trous passes, 29x29 pixels, stopped by "
                  "albedo, normal, depth and luminance differences) against low-frequency "
                  "blotches; auto: on for the models trained below 16 spp, off for the 16- and "
                  "64-spp ones; under work skipping the network then also computes 14 rows "
                  "around the needed ones")
              .add(&S::precision, "precision",
                  { { "auto", R::Auto }, { "fp32", R::Fp32 }, { "bf16", R::Bf16 } }, "precision",
                  "arithmetic of the network's convolutions: bf16 operands with fp32 sums, or "
                  "fp32; auto: bf16 where the CPU has AVX512_BF16 (on AMX tiles where it also has "
                  "AMX-BF16), else fp32; bf16 on a CPU without AVX512_BF16 is emulated (the same "
                  "results at fp32's speed); bf16 also takes cheaper approximations of the "
                  "network's input tone map and softmax exponential (relative errors below "
                  "1e-5); the 7x7 filters and the output stages are fp32 in every case; CPU "
                  "device only (CUDA runs its own half precision)")
              .add(&S::highlights, "highlights", 0.0, 1e6, "Highlight bypass",
                  "values of the colour inputs above this factor times the frame's bright "
                  "level (the power of two above the 99th percentile of the temporal "
                  "accumulation) skip the network's filters: the network reads them clamped and "
                  "the accumulation's excess is added back at its own pixel after the output's "
                  "post-filter (before its TAA when the post-filter is off), so a small light or "
                  "glint stays a point instead of a blotch; 0 = off")
              .add(&S::alphaMinHighSpp, "alphaMinHighSpp", 0.0, 1.0,
                  "Minimum blend factor (4 spp and more)",
                  "temporal accumulation with a model trained at 4 spp or more: weight of the "
                  "current frame once the history is long (alphaMin applies to the 1-spp "
                  "models); 0.5, chosen on training sequences: above 1 spp a shorter history "
                  "keeps the accumulated input sharper");
    return binding;
}

} // namespace afn::afnet
