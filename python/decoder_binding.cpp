// SPDX-License-Identifier: Apache-2.0
// Reading .ams streams: animcompress.Decoder (random access to frames), open(), info() and
// decode(). Frames are decoded straight into NumPy arrays without the GIL.
#include <algorithm>
#include <mutex>
#include <string>
#include <vector>

#include "module_support.h"

namespace animc::python {
namespace {

// An animc::Decoder with what it reads: the Python buffer it decodes in place (none for a
// file), and a mutex, because the library wants one thread per decoder and its calls run
// without the GIL.
class PyDecoder {
 public:
  PyDecoder(std::unique_ptr<HeldBuffer> buffer, Decoder decoder)
      : buffer_(std::move(buffer)), decoder_(std::move(decoder)) {}

  py::dict info() const { return infoDict(decoder_.info()); }
  py::array_t<uint32_t> faces() const { return facesArray(decoder_); }
  int64_t frameCount() const { return decoder_.info().frames; }

  py::array_t<float> frame(int64_t index) {
    const int64_t k = frameIndex(index, frameCount());
    py::array_t<float> xyz({py::ssize_t(decoder_.info().vertices), py::ssize_t(3)});
    float* out = xyz.mutable_data();
    throwIfError(unlocked([&] { return decoder_.frame(k, out); }));
    return xyz;
  }

  void verify() {
    throwIfError(unlocked([&] { return decoder_.verify(); }));
  }

 private:
  // Runs a decoder call without the GIL and under the decoder's own lock (taken only after
  // the GIL is let go, so that two threads cannot wait on each other).
  template <class Call>
  Status unlocked(const Call& call) {
    py::gil_scoped_release no_gil;
    std::lock_guard<std::mutex> lock(mutex_);
    return call();
  }

  std::unique_ptr<HeldBuffer> buffer_;  // declared first: outlives the decoder reading it
  Decoder decoder_;
  std::mutex mutex_;
};

// max_output_bytes comes last: open()'s arguments may be given by position.
std::unique_ptr<PyDecoder> openStream(py::handle path_or_bytes, py::object max_vertex_frames, int64_t max_bitplanes,
                                      int64_t max_payload_bytes, py::object max_output_bytes, int64_t threads,
                                      py::object max_multiply_adds) {
  const DecoderOptions options = decoderOptions(std::move(max_vertex_frames), std::move(max_output_bytes),
                                                max_bitplanes, max_payload_bytes, threads, std::move(max_multiply_adds));
  std::unique_ptr<HeldBuffer> buffer;
  Decoder decoder = openDecoder(path_or_bytes, options, buffer);
  return std::make_unique<PyDecoder>(std::move(buffer), std::move(decoder));
}

py::dict streamInfo(py::handle path_or_bytes) {
  std::unique_ptr<HeldBuffer> buffer;
  return infoDict(openDecoder(path_or_bytes, DecoderOptions{}, buffer).info());
}

// The frames decode() is asked for: None = all, a slice, or any iterable of indices (range,
// list, NumPy array), each checked by Python's rules. The array holds the selection's frames
// times the vertex count, at least what decoding them costs: a selection above
// max_vertex_frames, or whose array is above max_output_bytes, is refused before any list or
// array is made (repeated and strided selections included, which Decoder::checkDecodeWork does
// not see).
std::vector<int64_t> frameIndices(py::handle frames, const StreamInfo& info, const DecoderLimits& limits) {
  const uint64_t vertices = std::max<uint64_t>(info.vertices, 1);
  auto checkCount = [&](uint64_t count) {
    auto refuse = [&](const std::string& why) {
      throwIfError(Status(StatusCode::kLimitExceeded, "decode: " + std::to_string(count) + " frames of " +
                                                          std::to_string(info.vertices) + " vertices or more " + why));
    };
    if (count > limits.max_vertex_frames / vertices)
      refuse("are above the limit of " + std::to_string(limits.max_vertex_frames) +
             " vertex-frames; select fewer frames or raise max_vertex_frames");
    if (count > limits.max_output_bytes / (12 * vertices))
      refuse("take more than the limit of " + std::to_string(limits.max_output_bytes) +
             " bytes as float32; select fewer frames or raise max_output_bytes");
  };
  std::vector<int64_t> indices;
  if (frames.is_none()) {
    checkCount(uint64_t(info.frames));
    for (int64_t k = 0; k < info.frames; ++k) indices.push_back(k);
  } else if (py::isinstance<py::slice>(frames)) {
    py::ssize_t start = 0, stop = 0, step = 0, length = 0;
    if (!py::reinterpret_borrow<py::slice>(frames).compute(py::ssize_t(info.frames), &start, &stop, &step, &length))
      throw py::error_already_set();
    checkCount(uint64_t(length));
    for (py::ssize_t i = 0; i < length; ++i) indices.push_back(int64_t(start + i * step));
  } else {
    for (py::handle item : py::iter(frames)) {
      checkCount(indices.size() + 1);
      indices.push_back(frameIndex(integerValue(item), info.frames));
    }
  }
  return indices;
}

bool isAscendingRun(const std::vector<int64_t>& indices) {
  for (size_t i = 1; i < indices.size(); ++i)
    if (indices[i] != indices[0] + int64_t(i)) return false;
  return !indices.empty();
}

// An ascending run in one call (its groups decoded several at once), any other selection frame
// by frame.
Status decodeInto(Decoder& decoder, const std::vector<int64_t>& indices, float* out) {
  if (isAscendingRun(indices)) return decoder.frames(indices.front(), indices.back() + 1, out);
  const size_t stride = 3 * size_t(decoder.info().vertices);
  for (size_t i = 0; i < indices.size(); ++i) {
    Status s = decoder.frame(indices[i], out + i * stride);
    if (!s.ok()) return s;
  }
  return Status();
}

py::tuple decode(py::handle data, py::object frames, py::object max_vertex_frames, py::object max_output_bytes,
                 int64_t max_bitplanes, int64_t max_payload_bytes, int64_t threads, py::object max_multiply_adds) {
  const DecoderOptions options = decoderOptions(std::move(max_vertex_frames), std::move(max_output_bytes),
                                                max_bitplanes, max_payload_bytes, threads, std::move(max_multiply_adds));
  std::unique_ptr<HeldBuffer> buffer;
  Decoder decoder = openDecoder(data, options, buffer);
  // Refused before the index list is made: a stream may announce billions of frames.
  if (frames.is_none() && decoder.info().frames > 0) throwIfError(decoder.checkDecodeWork(0, decoder.info().frames));
  const std::vector<int64_t> indices = frameIndices(frames, decoder.info(), options.limits);
  // A run is refused before any work when over the limits; other selections frame by frame.
  if (isAscendingRun(indices)) throwIfError(decoder.checkDecodeWork(indices.front(), indices.back() + 1));
  py::array_t<float> xyz({py::ssize_t(indices.size()), py::ssize_t(decoder.info().vertices), py::ssize_t(3)});
  float* out = xyz.mutable_data();
  Status s;
  {
    py::gil_scoped_release unlocked;
    s = decodeInto(decoder, indices, out);
  }
  throwIfError(s);
  return py::make_tuple(xyz, facesArray(decoder));
}

}  // namespace

void bindDecoder(py::module_& module) {
  py::class_<PyDecoder>(module, "Decoder",
                        "An .ams stream opened for random access (animcompress.open); frames decode in any order.")
      .def("info", &PyDecoder::info, "The stream's header: codec, settings, counts, sizes (a dict).")
      .def_property_readonly("faces", &PyDecoder::faces, "The triangles, a (T, 3) uint32 array.")
      .def("frame", &PyDecoder::frame, py::arg("k"), "Frame k (negative counts from the end), an (N, 3) float32 array.")
      .def("__len__", &PyDecoder::frameCount)
      .def("__getitem__", &PyDecoder::frame, py::arg("k"))
      .def("verify", &PyDecoder::verify,
           "Checks every frame group and decodes every frame; raises Error if one is bad.");

  module.def("open", &openStream, py::arg("path_or_bytes"), py::arg("max_vertex_frames") = py::none(),
             py::arg("max_bitplanes") = 0, py::arg("max_payload_bytes") = 0, py::arg("max_output_bytes") = py::none(),
             py::arg("threads") = 0, py::arg("max_multiply_adds") = py::none(),
             "A Decoder over an .ams file (str or path-like) or bytes (kept referenced while it lives); threads: "
             "those a frame may use (0 = one per core), the frames are the same for any number. The max_ "
             "limits refuse larger work or output (animc decode's --max-vertex-frames, --max-output-bytes, "
             "--max-multiply-adds); None keeps the library's default.");
  module.def("info", &streamInfo, py::arg("path_or_bytes"), "The header of an .ams file or bytes, as Decoder.info().");
  module.def("decode", &decode, py::arg("data"), py::arg("frames") = py::none(), py::kw_only(),
             py::arg("max_vertex_frames") = py::none(), py::arg("max_output_bytes") = py::none(),
             py::arg("max_bitplanes") = 0, py::arg("max_payload_bytes") = 0, py::arg("threads") = 0,
             py::arg("max_multiply_adds") = py::none(),
             "(frames (F, N, 3) float32, faces (T, 3) uint32) of an .ams stream; `frames` selects frames by "
             "index, slice or range (all when None). A run of frames decodes its groups on `threads` threads "
             "at once (0 = one per core); the frames are the same for any number.");
}

}  // namespace animc::python
