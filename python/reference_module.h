// The submodule penumbra.reference (reference_module.cpp).
#pragma once

#include <pybind11/pybind11.h>

namespace penumbra::python {

void add_reference(pybind11::module_& parent);

}  // namespace penumbra::python
