// zsweep.generate's bindings (py_generate.cpp).
#pragma once

#include <pybind11/pybind11.h>

namespace zs::python {

void add_generate(pybind11::module_& m);

}  // namespace zs::python
