// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The declarations the Python module hands out (`models()`), as `sonargrid-cli models --json`
// gives them: split from sonargrid_module.cpp.

#include <pybind11/pybind11.h>

#include <vector>

#include "sonargrid/params/parameters.h"

namespace sg::python {

// The parameters as a list of dicts (name, symbol, unit, min, max, default, source, integer,
// description).
pybind11::list parameterList(const std::vector<ParameterSpec>& specs);
// The structure of `sonargrid-cli models --json`.
pybind11::dict modelsPy();

}  // namespace sg::python
