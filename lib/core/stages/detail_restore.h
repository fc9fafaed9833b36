// SPDX-License-Identifier: Apache-2.0
// Detail restoration: give the output back the noisy frame's own detail where the output departs
// from the frame by more than the frame's noise explains (parameter "restore"; not in any of the
// papers). Run by the Filter base on the final output of every method that demodulates.
//
// Why: every method's filter (and afn's networks) is made for a low sample count, where whatever
// departs from a smooth estimate is mostly noise. From 16 spp on the frame is close to clean, and
// a filter made for noisier input removes texture of the lighting, contact shadows and glossy
// detail as well: at 64 spp svgf and bmfr scored 1.4-1.7 dB below their own noisy input on
// afn-v4's held-out sequences, and afn's 16-spp model lost to the input on one of them
// (docs/afn-evaluation.md, "Detail restoration").
//
// Per pixel, in the albedo-demodulated domain (i = value / max(albedo, kAlbedoEpsilon); albedo 1
// without an albedo input):
//   n' = the frame's irradiance clamped per channel to the range of its 8 neighbours and of o
//        (o: the output's irradiance). A firefly is not detail: where the output removed it, it
//        is clamped to its neighbourhood; an edge has neighbours on both sides and passes; a value
//        the frame and the output both put beyond the neighbours (a small light, a glint) stays
//        as the method made it. n' always lies between o and the frame's value;
//   r  = n' - o, e = mean over channels of r;
//   s2 = the frame's noise variance (interpolated bilinearly between block centres): per 8x8
//        block, half the mean squared difference of horizontally adjacent values of mean_c(n'),
//        or of vertically adjacent ones, whichever is smaller (var(a - b) = 2 s^2 where both are
//        noise; an edge along one axis adds to one of the two only; other signal adds to both, so
//        the estimate errs towards keeping the output; a median would not, but it misses
//        heavy-tailed noise: dark scenes lost up to 0.8 dB with it);
//   m  = the 5x5 mean of e^2 (the residual's power: noise s^2 plus what the filter removed);
//   k  = clamp(1 - c s2 / m, 0, 1)   (a Wiener shrinkage; c = restoreNoise);
//   output' = output + k (n' - o) albedo.
// Where the filter removed only noise, m is about s2 and k = 0; where it removed detail far above
// the noise, k tends to 1. A convex blend of the output and the clamped frame: no value outside
// the two, nothing non-finite (the gathered colour is finite; a non-finite result keeps the
// output).
// auto: on from 16 spp (kAuxTrustedSpp, where the buffers are taken as clean too) and from twice
// the sample count the method was made for (Filter::samplesMadeFor: afn's model's training count;
// 1 for ta, svgf, bmfr and the learned baselines). Below 16 spp the noise is heavy-tailed (single
// bright samples among dark pixels) and the block estimate misses it: on afn's held-out output the
// first variants lost up to 1.1 dB on average at 4 spp and up to 4.8 at 1 spp. At the model's own
// count afn's output is already the better trade: with the 16-spp model at 16 spp it lost 0.6-0.7
// dB on two training sequences, where a glint the frame's samples missed was pulled towards the
// frame's dark value. c = 2, chosen on training sequences (docs/afn-evaluation.md, "Detail
// restoration"): the lowest temporal error for three of the four methods measured, PSNR within 0.12
// dB of the best.
#pragma once

#include "base/image.h"
#include "base/params.h"
#include "filter/frame.h"

#include <vector>

namespace afn {

/// Parameters "restore" and "restoreNoise" (in the table of every method that demodulates).
struct RestoreSettings {
    enum class Mode { Auto, Off, On };
    Mode restore = Mode::Auto;
    float noise = 2.0f; ///< c of the file comment: larger keeps more of the output
};

/// Descriptors of RestoreSettings.
const ParamBinding<RestoreSettings>& restoreBinding();

/// Whether the restoration runs for a colour input of `spp` samples per pixel (0 = unknown) and a
/// method made for `madeFor` samples per pixel.
bool restoreOn(const RestoreSettings& s, int spp, int madeFor);

/// The restoration's buffers, kept from frame to frame.
class DetailRestore {
public:
    /// Restore `output` (3 or more channels; the first three are changed) from `noisy`, the
    /// frame's colour as gathered (3 ch, finite; irradiance where frame.colorDemodulated), with
    /// the frame's albedo factors (stages/demodulate.h albedoFactorAt). `noisy` is consumed (it
    /// holds the frame's irradiance afterwards). Sizes must match.
    void run(Image& noisy, const Frame& frame, float noiseScale, const ImageView& output);
    /// Share of the last run's pixels with k > 0.5 (for the log; 0 before any run).
    double restoredShare() const { return m_restoredShare; }

    /// Two neighbouring noise blocks along a row or column and the second one's weight.
    struct BlockLerp {
        int i0, i1;
        float t;
    };

private:
    Image m_residual; ///< the output's irradiance, then n' - o (3 ch)
    Image m_mean; ///< mean_c(n') (1 ch), then the 5x5 box's horizontal sums of e^2
    Image m_power; ///< e^2 (1 ch)
    std::vector<float> m_blockNoise; ///< s2 per 8x8 block
    std::vector<BlockLerp> m_columns; ///< each column's blocks
    std::vector<int> m_restoredRows; ///< per row, the pixels given back more than half
    double m_restoredShare = 0.0;
};

} // namespace afn
