// SPDX-License-Identifier: Apache-2.0
// CRC-32 (ISO-HDLC, as the .ams sections use), for tests that forge a section.
export function crc32(bytes) {
  let crc = 0xffffffff;
  for (const b of bytes) {
    crc ^= b;
    for (let k = 0; k < 8; ++k) crc = (crc >>> 1) ^ (0xedb88320 & -(crc & 1));
  }
  return (crc ^ 0xffffffff) >>> 0;
}
