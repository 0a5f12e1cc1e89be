// SPDX-License-Identifier: Apache-2.0
// Binary adaptive range coder (carry-propagating, byte-wise output, 15-bit probabilities).
// Header-only so the per-bit calls inline into the codec loops. The decoder reads zeros past
// the end of its input and counts them; callers turn too many into kCorrupt.
#pragma once
#include <algorithm>
#include <cstdint>
#include <vector>

namespace animc {

constexpr int kProbBits = 15;
constexpr uint32_t kProbOne = 1u << kProbBits;

// The adaptation rate of a model, as a shift, for its update after `seen` earlier ones
// (which it counts): fast at first and then settling at 1/32, so that short streams (one
// frame of a small mesh) still learn their statistics. Bit models and symbol models
// (symbol_model.h) share it.
inline int nextAdaptationShift(uint16_t& seen) {
  static constexpr uint8_t kShift[] = {2, 3, 3, 4, 4, 4, 5, 5, 5, 5, 5, 5, 5};
  constexpr uint16_t kLearned = sizeof(kShift) - 1;  // from here on the rate stays 1/32
  // Almost every update of a busy model: a constant shift, no table load and no store of
  // `seen`.
  if (__builtin_expect(seen == kLearned, 1)) return kShift[kLearned];
  const int shift = kShift[seen];
  seen += seen < kLearned;
  return shift;
}

// Probability that the next bit is 0, adapting at nextAdaptationShift()'s rate.
struct BitModel {
  uint16_t p0 = kProbOne / 2;
  // Not uint8_t: a store through a char type may alias anything, which would force the
  // coders' range and code out of registers after every bit.
  uint16_t seen = 0;

  // For a bit the caller branches on.
  void update(int bit) {
    const int shift = nextShift();
    // p0 moves towards kProbOne after a 0 and towards 2^shift - 1 after a 1, by an arithmetic
    // shift: p0 + floor((2^shift - 1 - p0) / 2^shift) = p0 - floor(p0 / 2^shift), the same
    // rounding both ways as the two-sided form, with one shift instead of two.
    moveTowards(bit ? (1 << shift) - 1 : int32_t(kProbOne), shift);
  }
  // The same for a bit that is data (close to random), with a mask: GCC may turn update()'s
  // select into a branch, which suits well-predicted bits and mispredicts on these.
  void updateData(int bit) {
    const int shift = nextShift();
    moveTowards(int32_t(kProbOne) + ((((1 << shift) - 1) - int32_t(kProbOne)) & -bit), shift);
  }
  static uint32_t maskOf(int bit) { return 0u - uint32_t(bit); }

 private:
  int nextShift() { return nextAdaptationShift(seen); }
  void moveTowards(int32_t target, int shift) { p0 = uint16_t(int32_t(p0) + ((target - int32_t(p0)) >> shift)); }
};

// Raw bits that can be coded from `range` with one normalisation, after the last: each halves
// the range, and all but the last leave it at 2^24 or more, where normalise() does nothing.
// (At least one, which is what a bit at a time did, should a range below 2^24 ever come.)
inline int rawBitsBeforeNormalise(uint32_t range) { return std::max(1, (31 - __builtin_clz(range | 1)) - 23); }

// The decoder reads 4 bytes ahead and finish() writes 1 to 4, so after the last symbol the
// decoder may have read up to this many bytes past the encoder's output.
constexpr size_t kFinishReadAhead = 3;

class RangeEncoder {
 public:
  explicit RangeEncoder(std::vector<uint8_t>& out) : out_(out) {}

  void encode(BitModel& m, int bit) {
    const uint32_t bound = (range_ >> kProbBits) * m.p0;
    if (!bit) {
      range_ = bound;
    } else {
      low_ += bound;
      range_ -= bound;
    }
    m.update(bit);
    normalise();
  }
  // A symbol spanning [start, end) of 2^15 (symbol_model.h); the last span, which ends at
  // 2^15, takes whatever the scaled spans leave of the range, as a 1 bit does above.
  void encodeSpan(uint32_t start, uint32_t end) {
    const uint32_t unit = range_ >> kProbBits;
    low_ += unit * start;
    range_ = (end < kProbOne ? unit * end : range_) - unit * start;
    normalise();
  }
  // Equiprobable bits (signs, low mantissa bits): no model, no adaptation.
  void encodeRaw(uint32_t value, int bits) {
    while (bits > 0) {  // runs of bits with one normalise() after each
      const int run = std::min(bits, rawBitsBeforeNormalise(range_));
      for (int i = bits - 1; i >= bits - run; --i) {
        range_ >>= 1;
        if ((value >> i) & 1) low_ += range_;
      }
      bits -= run;
      normalise();
    }
  }
  // Ends the stream with the fewest bytes (1 to 4) that pin the decoder's code inside the
  // final range whatever follows them: the decoder reads on into the next stream or into
  // zeros, and any such continuation decodes the same. The range spans at least 2^24, so two
  // bytes always do; one does unless the range straddles a multiple of 2^24 badly. (Four
  // bytes every time are a noticeable share of a small frame at coarse errors.)
  void finish() {
    int bytes = 1;
    uint64_t value = low_;
    for (; bytes < 4; ++bytes) {
      const uint64_t unit = uint64_t(1) << (32 - 8 * bytes);  // what the bytes after them weigh
      value = (low_ + unit - 1) & ~(unit - 1);
      if (value + unit <= low_ + range_) break;
    }
    if (bytes == 4) value = low_;
    low_ = value;
    // The last call moves a zero byte in (value's bytes below the kept ones are zero), which
    // sends out the cache and any pending 0xFF bytes.
    for (int i = 0; i <= bytes; ++i) shiftLow();
  }

 private:
  void normalise() {
    while (range_ < (1u << 24)) {
      range_ <<= 8;
      shiftLow();
    }
  }
  void shiftLow() {
    if (uint32_t(low_) < 0xFF000000u || (low_ >> 32) != 0) {
      const uint8_t carry = uint8_t(low_ >> 32);
      if (has_cache_) out_.push_back(uint8_t(cache_ + carry));
      for (; pending_ff_ > 0; --pending_ff_) out_.push_back(uint8_t(0xFF + carry));
      cache_ = uint8_t(low_ >> 24);
      has_cache_ = true;
    } else {
      ++pending_ff_;
    }
    low_ = (low_ & 0x00FFFFFFu) << 8;
  }

  std::vector<uint8_t>& out_;
  uint64_t low_ = 0;
  uint32_t range_ = 0xFFFFFFFFu;
  uint8_t cache_ = 0;
  bool has_cache_ = false;
  uint64_t pending_ff_ = 0;
};

class RangeDecoder {
 public:
  RangeDecoder(const uint8_t* data, size_t size) : p_(data), end_(data + size) {
    for (int i = 0; i < 4; ++i) code_ = (code_ << 8) | nextByte();
  }

  // A bit the caller branches on: the compiler may branch here too, which lets a well
  // predicted bit start the next decode before this one's comparison resolves.
  int decode(BitModel& m) {
    const uint32_t bound = (range_ >> kProbBits) * m.p0;
    const int bit = code_ >= bound;
    code_ -= bit ? bound : 0;
    range_ = bit ? range_ - bound : bound;
    m.update(bit);
    normalise();
    return bit;
  }
  // A bit that only becomes data (a sign, a mantissa bit): masks instead of branches, since
  // such bits are close to random and a branch on them is mispredicted half the time.
  int decodeData(BitModel& m) {
    const int bit = decodeWithProbability(m.p0);
    m.update(bit);
    return bit;
  }
  // decodeData() given the model's probability, for callers that fetch it ahead of time;
  // they update the model themselves.
  int decodeWithProbability(uint32_t p0) {
    const uint32_t bound = (range_ >> kProbBits) * p0;
    const int bit = code_ >= bound;
    const uint32_t mask = BitModel::maskOf(bit);
    code_ -= bound & mask;
    range_ = bound + ((range_ - bound - bound) & mask);  // range_ - bound when the bit is 1
    normalise();
    return bit;
  }
  // A symbol in two steps (symbol_model.h): the value in 15-bit units that the coded span
  // holds, capped below 2^15 (the last span also holds what lies beyond), then the span.
  uint32_t spanTarget() const {
    const uint32_t target = code_ / (range_ >> kProbBits);
    return target < kProbOne - 1 ? target : kProbOne - 1;
  }
  void decodeSpan(uint32_t start, uint32_t end) {
    const uint32_t unit = range_ >> kProbBits;
    code_ -= unit * start;
    range_ = (end < kProbOne ? unit * end : range_) - unit * start;
    normalise();
  }
  uint32_t decodeRaw(int bits) {
    uint32_t v = 0;
    while (bits > 0) {
      // As in encodeRaw(): runs of bits with one normalise() after each.
      const int run = std::min(bits, rawBitsBeforeNormalise(range_));
      for (int i = 0; i < run; ++i) {
        range_ >>= 1;
        v = (v << 1) | uint32_t(code_ >= range_);
        // code_ - range_ wraps above code_ exactly when the bit is 0.
        code_ = std::min(code_, code_ - range_);
      }
      bits -= run;
      normalise();
    }
    return v;
  }
  // A valid stream leaves the decoder at most kFinishReadAhead bytes past its end (4 were
  // allowed when finish() wrote 4 bytes, and still are); a corrupt one either reads far past
  // its end or leaves the code outside the range.
  bool overran() const { return overrun_ > 4 || code_ >= range_; }
  // The next byte the decoder would read (it reads 4 bytes ahead of the bits decoded).
  const uint8_t* position() const { return p_; }

 private:
  void normalise() {
    while (range_ < (1u << 24)) {
      range_ <<= 8;
      code_ = (code_ << 8) | nextByte();
    }
  }
  uint8_t nextByte() {
    if (p_ < end_) return *p_++;
    ++overrun_;
    return 0;
  }

  const uint8_t* p_;
  const uint8_t* end_;
  uint32_t code_ = 0;
  uint32_t range_ = 0xFFFFFFFFu;
  uint32_t overrun_ = 0;
};

}  // namespace animc
