// SPDX-License-Identifier: Apache-2.0
// Equiprobable bits kept out of the range coder: written after its bytes, in reverse, so a
// payload holds both streams without a length field (the range decoder reads from the front,
// this reader from the back). Taking a bit here costs a shift, not a step of the range
// coder's serial chain. (Opus's range coder places its raw bits the same way.)
#pragma once
#include <cstddef>
#include <cstdint>
#include <vector>

namespace animc {

class RawBitWriter {
 public:
  // bits <= 32, most significant first.
  void write(uint32_t value, int bits) {
    for (int i = bits - 1; i >= 0; --i) {
      current_ = uint8_t((current_ << 1) | ((value >> i) & 1));
      if (++filled_ == 8) flushByte();
    }
  }
  // Appends the bits to out, last byte first; a partial byte is padded with zeros.
  void appendTo(std::vector<uint8_t>& out) {
    if (filled_ > 0) {
      current_ = uint8_t(current_ << (8 - filled_));
      flushByte();
    }
    out.insert(out.end(), bytes_.rbegin(), bytes_.rend());
  }

 private:
  void flushByte() {
    bytes_.push_back(current_);
    current_ = 0;
    filled_ = 0;
  }
  std::vector<uint8_t> bytes_;
  uint8_t current_ = 0;
  int filled_ = 0;
};

class RawBitReader {
 public:
  RawBitReader(const uint8_t* data, size_t size) : begin_(data), p_(data + size) {}

  // bits <= 32. Past the start of the data it reads zeros.
  uint32_t read(int bits) {
    if (count_ < bits) refill();
    const uint32_t value = uint32_t((buffer_ >> (63 - bits)) >> 1);  // 0 when bits is 0
    buffer_ <<= bits;
    count_ -= bits;
    return value;
  }
  // Bytes at the end of the data that the bits read so far came from (the reader fetches
  // ahead, which this leaves out), for the check that the two streams do not overlap.
  size_t bytesUsed() const { return (8 * taken_ - size_t(count_) + 7) / 8; }
  // Whether a bit was read from before the start of the data.
  bool overran() const { return zero_bits_ > size_t(count_); }

 private:
  // Bits after the first zero of padding are all padding, so once padding has come in, the
  // buffer's last zero_bits_ bits (or all of it) are padding.
  void refill() {
    while (count_ <= 56) {
      uint8_t byte = 0;
      if (p_ > begin_) {
        byte = *--p_;
      } else {
        zero_bits_ += 8;
      }
      ++taken_;
      buffer_ |= uint64_t(byte) << (56 - count_);
      count_ += 8;
    }
  }
  const uint8_t* begin_;
  const uint8_t* p_;
  uint64_t buffer_ = 0;  // unread bits, at the top
  int count_ = 0;
  size_t taken_ = 0;      // bytes moved into the buffer, padding included
  size_t zero_bits_ = 0;  // padding bits moved into the buffer
};

}  // namespace animc
