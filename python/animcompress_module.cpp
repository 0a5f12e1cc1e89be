// SPDX-License-Identifier: Apache-2.0
// The animcompress Python module: encode(), compare(), codecs(), __version__ and Error here;
// the reading side (Decoder, open, info, decode) in decoder_binding.cpp. Everything goes
// through the public API, animc/animc.h, so Python writes the bytes `animc encode` writes.
#include <limits>
#include <memory>
#include <string>
#include <type_traits>
#include <vector>

#include <pybind11/stl.h>

#include "module_support.h"

namespace animc::python {
namespace {

using FloatArray = py::array_t<float, py::array::c_style | py::array::forcecast>;

// frames as a C-contiguous float32 (F, N, 3) array (converted by NumPy, not by a Python
// loop), or ValueError naming the argument.
FloatArray framesArray(py::handle frames, const char* name) {
  FloatArray array = FloatArray::ensure(frames);
  if (!array || array.ndim() != 3 || array.shape(2) != 3)
    throw py::value_error(std::string(name) + ": expected an array of floats shaped (frames, vertices, 3)");
  if (array.shape(1) > py::ssize_t(std::numeric_limits<uint32_t>::max()))
    throw py::value_error(std::string(name) + ": more than 2^32 - 1 vertices");
  return array;
}

template <class T>
void appendIndices(const py::array& faces, std::vector<uint32_t>& out) {
  auto values = py::array_t<T, py::array::c_style | py::array::forcecast>::ensure(faces);
  if (!values) throw py::value_error("faces: not convertible to integers");
  const T* v = values.data();
  for (py::ssize_t i = 0; i < values.size(); ++i) {
    bool negative = false;
    if constexpr (std::is_signed_v<T>) negative = v[i] < 0;
    if (negative || uint64_t(v[i]) > std::numeric_limits<uint32_t>::max())
      throw py::value_error("faces: vertex index " + std::to_string(v[i]) + " is not a uint32");
    out.push_back(uint32_t(v[i]));
  }
}

// faces as 3 * T uint32 indices; ValueError for another shape, non-integers, or an index
// that a uint32 cannot hold (indices past the vertex count are the library's to refuse).
std::vector<uint32_t> triangleIndices(py::handle faces) {
  py::array array = py::array::ensure(faces);
  if (!array || array.ndim() != 2 || array.shape(1) != 3)
    throw py::value_error("faces: expected an integer array shaped (triangles, 3)");
  const char kind = array.dtype().kind();
  if (kind != 'i' && kind != 'u')
    throw py::value_error("faces: expected integers, not " + py::str(array.dtype()).cast<std::string>());
  std::vector<uint32_t> indices;
  indices.reserve(size_t(array.size()));
  if (kind == 'u')
    appendIndices<uint64_t>(array, indices);
  else
    appendIndices<int64_t>(array, indices);
  return indices;
}

// One keyword option as EncoderOptions::set takes it: a switch is "1" when true and left out
// when false; a float goes through set(double), which writes it so that it parses back exact.
void setOption(EncoderOptions& options, const std::string& name, py::handle value) {
  if (py::isinstance<py::bool_>(value)) {
    if (value.cast<bool>()) options.set(name, "1");
  } else if (PyIndex_Check(value.ptr())) {
    options.set(name, py::str(py::reinterpret_steal<py::object>(PyNumber_Index(value.ptr()))).cast<std::string>());
  } else if (PyFloat_Check(value.ptr())) {
    options.set(name, value.cast<double>());
  } else if (py::isinstance<py::str>(value)) {
    options.set(name, value.cast<std::string>());
  } else {
    throw py::type_error("option " + name + ": expected a bool, int, float or str");
  }
}

EncoderOptions encoderOptions(const std::string& codec, int64_t iframe_interval, double frame_rate, int64_t threads,
                              int64_t connectivity_piece, const py::kwargs& keywords) {
  if (iframe_interval < 0 || iframe_interval > int64_t(std::numeric_limits<uint32_t>::max()))
    throw py::value_error("iframe_interval must be in [0, 2^32 - 1]");
  if (connectivity_piece < 0 || connectivity_piece > int64_t(std::numeric_limits<uint32_t>::max()))
    throw py::value_error("connectivity_piece must be in [0, 2^32 - 1]");
  EncoderOptions options;
  options.codec = codec;
  options.iframe_interval = uint32_t(iframe_interval);
  options.frame_rate = frame_rate;
  options.threads = threadCount(threads);
  options.connectivity_piece = uint32_t(connectivity_piece);
  for (auto [key, value] : keywords) {
    std::string name = key.cast<std::string>();
    for (char& c : name) c = c == '_' ? '-' : c;  // max_error -> max-error, as animc's flags
    setOption(options, name, value);
  }
  return options;
}

Status encodeFrames(const EncoderOptions& options, const std::vector<float>& frames, uint32_t vertex_count,
                    const std::vector<uint32_t>& triangles, std::vector<uint8_t>& bytes) {
  auto created = Encoder::create(options, vertex_count, triangles.data(), triangles.size() / 3, memorySink(&bytes));
  if (!created.ok()) return created.status();
  Encoder& encoder = created.value();
  const size_t stride = 3 * size_t(vertex_count);
  for (size_t f = 0; stride > 0 && f < frames.size() / stride; ++f) {
    Status s = encoder.addFrame(frames.data() + f * stride);
    if (!s.ok()) return s.withContext("frame " + std::to_string(f));
  }
  return encoder.finish().status();
}

py::bytes encode(py::handle frames, py::handle faces, const std::string& codec, int64_t iframe_interval,
                 double frame_rate, int64_t threads, int64_t connectivity_piece, const py::kwargs& keywords) {
  const EncoderOptions options =
      encoderOptions(codec, iframe_interval, frame_rate, threads, connectivity_piece, keywords);
  const FloatArray xyz = framesArray(frames, "frames");
  // Owned copies: the coding runs without the GIL, while other threads could change arrays.
  const std::vector<float> owned(xyz.data(), xyz.data() + xyz.size());
  const std::vector<uint32_t> triangles = triangleIndices(faces);
  const uint32_t vertex_count = uint32_t(xyz.shape(1));
  std::vector<uint8_t> bytes;
  Status s;
  {
    py::gil_scoped_release unlocked;
    s = encodeFrames(options, owned, vertex_count, triangles, bytes);
  }
  throwIfError(s);
  return py::bytes(reinterpret_cast<const char*>(bytes.data()), bytes.size());
}

// The bytes of one .ams stream joined from parts (paths or bytes), as animc join.
py::bytes join(const py::sequence& parts) {
  std::vector<std::unique_ptr<HeldBuffer>> held;
  std::vector<StreamPart> refs;
  for (size_t i = 0; i < parts.size(); ++i) {
    py::handle part = parts[i];
    if (isPath(part)) {
      refs.push_back({pathText(part)});
      continue;
    }
    held.push_back(std::make_unique<HeldBuffer>(part));
    refs.push_back({"part " + std::to_string(i), held.back()->data(), held.back()->size()});
  }
  std::vector<uint8_t> bytes;
  Result<uint64_t> joined = uint64_t(0);
  {
    py::gil_scoped_release unlocked;
    joined = joinStreams(refs, memorySink(&bytes));
  }
  throwIfError(joined.status());
  return py::bytes(reinterpret_cast<const char*>(bytes.data()), bytes.size());
}

py::dict metricsDict(const SequenceMetrics& m) {
  py::array_t<double> rms(py::ssize_t(m.per_frame.size()));
  py::array_t<double> max(py::ssize_t(m.per_frame.size()));
  for (size_t f = 0; f < m.per_frame.size(); ++f) {
    rms.mutable_at(f) = m.per_frame[f].rms;
    max.mutable_at(f) = m.per_frame[f].max;
  }
  py::dict d;
  d["kg_error"] = m.kg_error;
  d["psnr"] = m.psnr;
  d["max_error"] = m.max_error;
  d["max_error_rel_diag"] = m.max_error_rel_diag;
  d["max_error_rel_cube"] = m.max_error_rel_cube;
  d["rms_error"] = m.rms_error;
  d["rms_error_rel_diag"] = m.rms_error_rel_diag;
  d["bbox_diagonal"] = m.bbox_diagonal;
  d["frames"] = m.frames;
  d["vertices"] = m.vertices;
  d["per_frame"] = py::dict(py::arg("rms") = rms, py::arg("max") = max);
  return d;
}

py::dict compare(py::handle original, py::handle reconstructed, py::handle faces) {
  const FloatArray a = framesArray(original, "original");
  const FloatArray b = framesArray(reconstructed, "reconstructed");
  if (a.shape(0) != b.shape(0) || a.shape(1) != b.shape(1))
    throw py::value_error("original and reconstructed differ in shape");
  const uint32_t vertex_count = uint32_t(a.shape(1));
  const size_t stride = 3 * size_t(vertex_count);
  // Faces are checked before any work; both figures come from one pass over the frames.
  std::unique_ptr<StedAccumulator> sted;
  if (!faces.is_none()) {
    const std::vector<uint32_t> triangles = triangleIndices(faces);
    sted = std::make_unique<StedAccumulator>(vertex_count, triangles.data(), triangles.size() / 3);
  }
  MetricsAccumulator metrics(vertex_count, PerFrameErrors::kKeep);
  for (py::ssize_t f = 0; f < a.shape(0); ++f) {
    metrics.addFrame(a.data() + f * stride, b.data() + f * stride);
    if (sted) sted->addFrame(a.data() + f * stride, b.data() + f * stride);
  }
  py::dict figures = metricsDict(metrics.finish());
  if (!sted) return figures;
  const StedFigures s = sted->finish();
  figures["sted"] = s.sted;
  figures["sted_spatial"] = s.spatial;
  figures["sted_temporal"] = s.temporal;
  return figures;
}

}  // namespace
}  // namespace animc::python

PYBIND11_MODULE(animcompress, module) {
  namespace py = pybind11;
  using namespace animc::python;
  module.doc() = "Compression of animated triangle meshes into .ams streams (the animcompress library).";
  defineErrorClass(module);
  module.attr("__version__") = animc::animcVersion();
  module.def("codecs", &animc::codecNames, "The codecs this build writes and reads, by name.");
  module.def("encode", &encode, py::arg("frames"), py::arg("faces"), py::arg("codec") = "affine-octree",
             py::arg("iframe_interval") = 0, py::arg("frame_rate") = 25.0, py::arg("threads") = 0,
             py::arg("connectivity_piece") = animc::kDefaultConnectivityPiece,
             "The .ams bytes of frames (F, N, 3) over faces (T, 3), coded on `threads` threads (0 = one per "
             "core; the bytes are the same for any number). Faces are coded in pieces of connectivity_piece "
             "triangles that decode at once; more than one piece makes an .ams format 2 stream, which "
             "animcompress before 1.2 cannot read (0 = one piece, format 1). Keyword options are the codec's "
             "(max_error=0.01 is animc encode's --max-error 0.01; True sets a switch). The codec is "
             "'affine-octree' unless codec= says otherwise, as in the C++ library and in 1.0, so that 1.0 "
             "programs and their options (profile=, bits=) keep working; animc encode and the MeshLab filter "
             "default to 'auto', the smallest files at about affine-octree's speed: pass codec='auto' to write "
             "what animc writes.");
  module.def("join", &join, py::arg("parts"),
             "The .ams bytes of consecutive parts of one sequence (files or bytes) encoded apart with the same "
             "settings, as animc join: those of encoding the whole sequence at once when every part but the last "
             "is a whole number of iframe_interval frames.");
  module.def("compare", &compare, py::arg("original"), py::arg("reconstructed"), py::arg("faces") = py::none(),
             "The error figures (KG, PSNR, max and RMS errors, per frame) of a reconstruction, as animc compare; "
             "with faces (T, 3), STED too (sted, sted_spatial, sted_temporal).");
  bindDecoder(module);
}
