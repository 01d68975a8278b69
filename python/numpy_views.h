// numpy arrays as the library's views (penumbra/image_view.h) and Images as
// numpy arrays, for the Python module (penumbra_module.cpp, reference_module.cpp).
//
// Images are (H, W) for one channel or (C, H, W); the memory order is read
// from the strides: (C, H, W) with unit pixel stride is planar (rows and
// planes at any pitch), with pixel stride C and unit channel stride
// interleaved (an (H, W, C) array seen through transpose(2, 0, 1)).
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <string>
#include <utility>
#include <vector>

#include "penumbra/image.h"
#include "penumbra/image_view.h"

namespace penumbra::python {

namespace py = pybind11;

// Throws Error(InvalidArgument, op, parameter, message).
[[noreturn]] void refuse(const std::string& op, const std::string& parameter, const std::string& message);

// An input array as a view; `keep` holds the array (or its float32 or
// contiguous copy, for another dtype or strides no view can express).
ImageView input_view(const py::object& object, const std::string& op, const std::string& parameter,
                     py::array& keep);

// `out` as given (written in place: float32, writable, a layout a view
// takes), or a new float32 array of `shape`.
std::pair<py::array, MutableImageView> output_view(const py::object& out, std::vector<py::ssize_t> shape,
                                                  const std::string& op);

// The image as a numpy array over its own pixels (no copy; the array owns
// the image): (H, W) for one channel, else (C, H, W).
py::array to_numpy(Image image);

}  // namespace penumbra::python
