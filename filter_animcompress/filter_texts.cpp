// SPDX-License-Identifier: GPL-3.0-or-later
#include "filter_texts.h"

namespace animc::meshlab {

QString filterTitle(int id) {
  switch (id) {
    case kCompressFilter: return "Compress Animation Layers";
    case kReconstructionErrorFilter: return "Animation Reconstruction Error";
    case kImportFilter: return "Import Compressed Animation";
  }
  return {};
}

QString filterDescription(int id) {
  switch (id) {
    case kCompressFilter:
      return "Compresses an animation whose frames are the layers of the document (same vertices "
             "and triangles in every layer, in document order) into an .ams file with the "
             "animcompress codec library, then logs its size, bits per vertex per frame, "
             "Karni-Gotsman error, PSNR and max error. Optionally adds the frames a decoder will "
             "reconstruct as new layers and colours them by per-vertex error.";
    case kReconstructionErrorFilter:
      return "Compares two runs of layers (original frames and reconstructed ones) frame by frame. "
             "Each reconstructed vertex gets its error as vertex quality and a colour from blue "
             "(exact) to red (the colour scale's maximum, the same for every frame). Logs the RMS "
             "and max error of each frame and the figures of the whole animation.";
    case kImportFilter:
      return "Decodes an animcompress .ams file (all frames or a range) into one new layer per "
             "frame, labelled frame_00000, frame_00001, ... by frame number.";
  }
  return {};
}

}  // namespace animc::meshlab
