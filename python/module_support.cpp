// SPDX-License-Identifier: Apache-2.0
#include "module_support.h"

#include <cstring>
#include <limits>
#include <string>
#include <variant>

namespace animc::python {
namespace {

// animcompress.Error, owned for the life of the process: a module's exception class is never
// freed before the interpreter ends, and a static py::object would be released after it.
PyObject* error_class = nullptr;

// A keyword count that must be a non-negative integer, as the library's unsigned fields are.
uint64_t nonNegative(int64_t value, const char* name) {
  if (value < 0) throw py::value_error(std::string(name) + " must be >= 0, not " + std::to_string(value));
  return uint64_t(value);
}

py::object settingValue(const SettingValue& setting) {
  return std::visit([](const auto& value) -> py::object { return py::cast(value); }, setting.value);
}

}  // namespace

void defineErrorClass(py::module_& module) {
  error_class =
      PyErr_NewExceptionWithDoc("animcompress.Error",
                                "A failure the library reported: str() is its message, .code the status code's name "
                                "('truncated', 'corrupt', 'i/o error', 'limit exceeded', ...).",
                                PyExc_Exception, nullptr);
  if (error_class == nullptr) throw py::error_already_set();
  py::handle(error_class).attr("code") = py::none();
  module.add_object("Error", py::handle(error_class));
}

void throwIfError(const Status& status) {
  if (status.ok()) return;
  py::object error = py::handle(error_class)(status.message());
  error.attr("code") = statusCodeName(status.code());
  PyErr_SetObject(error_class, error.ptr());
  throw py::error_already_set();
}

HeldBuffer::HeldBuffer(py::handle object) : owner_(py::reinterpret_borrow<py::object>(object)) {
  if (PyObject_GetBuffer(owner_.ptr(), &view_, PyBUF_SIMPLE) != 0) throw py::error_already_set();
  if (view_.readonly) return;
  py::bytes copy(static_cast<const char*>(view_.buf), size_t(view_.len));
  PyBuffer_Release(&view_);
  owner_ = std::move(copy);
  if (PyObject_GetBuffer(owner_.ptr(), &view_, PyBUF_SIMPLE) != 0) throw py::error_already_set();
}

HeldBuffer::~HeldBuffer() { PyBuffer_Release(&view_); }

bool isPath(py::handle object) { return py::isinstance<py::str>(object) || py::hasattr(object, "__fspath__"); }

std::string pathText(py::handle object) {
  return py::module_::import("os").attr("fsdecode")(object).cast<std::string>();
}

int64_t integerValue(py::handle item) {
  py::object index = py::reinterpret_steal<py::object>(PyNumber_Index(item.ptr()));
  if (!index) throw py::error_already_set();
  const long long value = PyLong_AsLongLong(index.ptr());
  if (value == -1 && PyErr_Occurred()) throw py::error_already_set();
  return value;
}

uint32_t threadCount(int64_t threads) {
  if (threads < 0 || threads > 1024) throw py::value_error("threads must be in [0, 1024] (0 = one per core)");
  return uint32_t(threads);
}

DecoderOptions decoderOptions(py::object max_vertex_frames, py::object max_output_bytes, int64_t max_bitplanes,
                              int64_t max_payload_bytes, int64_t threads, py::object max_multiply_adds) {
  DecoderOptions options;
  options.threads = threadCount(threads);
  if (!max_vertex_frames.is_none())
    options.limits.max_vertex_frames = nonNegative(integerValue(max_vertex_frames), "max_vertex_frames");
  if (!max_output_bytes.is_none())
    options.limits.max_output_bytes = nonNegative(integerValue(max_output_bytes), "max_output_bytes");
  if (!max_multiply_adds.is_none())
    options.limits.max_multiply_adds = nonNegative(integerValue(max_multiply_adds), "max_multiply_adds");
  if (max_bitplanes > std::numeric_limits<int>::max()) throw py::value_error("max_bitplanes is too large");
  options.progressive.max_bitplanes = int(nonNegative(max_bitplanes, "max_bitplanes"));
  options.progressive.max_payload_bytes = nonNegative(max_payload_bytes, "max_payload_bytes");
  return options;
}

Decoder openDecoder(py::handle path_or_bytes, const DecoderOptions& options, std::unique_ptr<HeldBuffer>& buffer) {
  // Opening checks the first frame group, real work: done without the GIL.
  if (isPath(path_or_bytes)) {
    const std::string path = pathText(path_or_bytes);
    return valueOrThrow([&] {
      py::gil_scoped_release unlocked;
      return Decoder::openFile(path, options);
    }());
  }
  buffer = std::make_unique<HeldBuffer>(path_or_bytes);
  return valueOrThrow([&] {
    py::gil_scoped_release unlocked;
    return Decoder::openMemory(buffer->data(), buffer->size(), options);
  }());
}

py::dict infoDict(const StreamInfo& info) {
  py::dict settings;
  for (const SettingValue& setting : info.settings) settings[py::str(setting.key)] = settingValue(setting);
  py::dict d;
  d["format_version"] = info.format_version;
  d["codec"] = info.codec;
  d["codec_id"] = info.codec_id;
  d["settings"] = settings;
  d["settings_text"] = info.settings_text;
  d["vertices"] = info.vertices;
  d["triangles"] = info.triangles;
  d["frames"] = info.frames;
  d["frame_rate"] = info.frame_rate;
  d["iframe_interval"] = info.iframe_interval;
  d["groups"] = info.groups;
  d["bytes"] = info.bytes;
  d["static_bytes"] = info.static_bytes;
  return d;
}

py::array_t<uint32_t> facesArray(const Decoder& decoder) {
  const py::ssize_t count = py::ssize_t(decoder.info().triangles);
  py::array_t<uint32_t> faces({count, py::ssize_t(3)});
  if (count > 0) std::memcpy(faces.mutable_data(), decoder.triangles(), size_t(count) * 3 * sizeof(uint32_t));
  return faces;
}

int64_t frameIndex(int64_t index, int64_t count) {
  const int64_t k = index < 0 ? index + count : index;
  if (k < 0 || k >= count)
    throw py::index_error("frame " + std::to_string(index) + " outside a stream of " + std::to_string(count) +
                          " frames");
  return k;
}

}  // namespace animc::python
