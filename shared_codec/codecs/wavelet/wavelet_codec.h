// SPDX-License-Identifier: Apache-2.0
// The wavelet codec (Guskov & Khodakovsky 2004) as seen by the container. Three frame types:
// a parametric frame (the first frame of every group: positions through the static
// StaticPositionCoder, then the hierarchy is rebuilt on its reconstruction), and detail I- and
// P-frames (bitplane-coded wavelet coefficients, P-frames against a damped linear
// extrapolation of the previous frames' reconstructed coefficients). docs/wavelet.md describes the payloads.
#pragma once
#include <memory>

#include "codecs/frame_codec.h"
#include "codecs/wavelet/options.h"
#include "core/simd_math.h"

namespace animc {

// kDetailPredicted is followed by one byte of prediction selectors (docs/wavelet.md).
enum class WaveletFrameType : uint8_t { kParametric = 0, kDetailIntra = 1, kDetailPredicted = 2 };

// path: the kernels' version (core/simd_math.h), the same bytes and frames either way.
std::unique_ptr<FrameEncoder> makeWaveletEncoder(const WaveletOptions& options, const Topology& topology,
                                                 SimdPath path);
// control: progressive decoding (fewer bitplanes, fewer bytes per frame); {} decodes
// everything. A P-frame decoded with less than the encoder sent drifts from the encoder's
// reconstruction until the next parametric frame.
std::unique_ptr<FrameDecoder> makeWaveletDecoder(const WaveletOptions& options, const Topology& topology,
                                                 const WaveletDecodeControl& control, SimdPath path);

}  // namespace animc
