// SPDX-License-Identifier: Apache-2.0
// Pieces shared by the animcompress module's source files: turning a Status into
// animcompress.Error, holding a Python buffer while the library reads it in place, decoder
// options from keyword arguments, and the info() dictionary. Only the public API is used.
#pragma once
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <cstdint>
#include <memory>

#include "animc/animc.h"

namespace animc::python {

namespace py = pybind11;

// Creates animcompress.Error in `module`; raiseStatus() needs it first.
void defineErrorClass(py::module_& module);
// Raises animcompress.Error (str = the message, .code = statusCodeName) for a failed status;
// needs the GIL, so code that released it returns its Status and checks it afterwards.
void throwIfError(const Status& status);

template <class T>
T valueOrThrow(Result<T> result) {
  throwIfError(result.status());
  return std::move(result).value();
}

// The bytes of a Python object with the buffer protocol, contiguous, held until destroyed
// (a bytearray cannot be resized meanwhile). A writable buffer is copied into a bytes object
// first: the library reads without the GIL, when another thread could change it.
class HeldBuffer {
 public:
  explicit HeldBuffer(py::handle object);
  HeldBuffer(const HeldBuffer&) = delete;
  HeldBuffer& operator=(const HeldBuffer&) = delete;
  ~HeldBuffer();
  const void* data() const { return view_.buf; }
  size_t size() const { return size_t(view_.len); }

 private:
  py::object owner_;  // the object read, or the copy of a writable one
  Py_buffer view_{};
};

// Whether an argument names a file (str or os.PathLike) rather than holding the stream.
bool isPath(py::handle object);
std::string pathText(py::handle object);

// An integer as Python takes an index (int, NumPy integer; not a float), else TypeError.
int64_t integerValue(py::handle item);

// The threads= argument of encode(), decode() and open(): 0 = one per core, else at most 1024.
uint32_t threadCount(int64_t threads);

// DecoderOptions from the keyword arguments of open() and decode(); None keeps the default.
DecoderOptions decoderOptions(py::object max_vertex_frames, py::object max_output_bytes, int64_t max_bitplanes,
                              int64_t max_payload_bytes, int64_t threads, py::object max_multiply_adds);

// A decoder over a file or over a buffer that `buffer` holds (left empty for a file).
Decoder openDecoder(py::handle path_or_bytes, const DecoderOptions& options, std::unique_ptr<HeldBuffer>& buffer);

py::dict infoDict(const StreamInfo& info);
// The triangles as a (T, 3) uint32 array (a copy, so it outlives the decoder).
py::array_t<uint32_t> facesArray(const Decoder& decoder);
// Python's index rules: -1 is the last; IndexError outside [-count, count).
int64_t frameIndex(int64_t index, int64_t count);

void bindDecoder(py::module_& module);

}  // namespace animc::python
