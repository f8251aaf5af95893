#pragma once
// geodual's JSON reports as Python objects: objects become dicts (keys in
// order), arrays lists, null None, numbers int or float.

#include <pybind11/pybind11.h>
#include <nlohmann/json.hpp>

namespace geodual::python {

pybind11::object json_to_python(const nlohmann::ordered_json& json);

}  // namespace geodual::python
