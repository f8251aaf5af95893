#include "json_to_python.hpp"

namespace geodual::python {

namespace py = pybind11;

py::object json_to_python(const nlohmann::ordered_json& json) {
  switch (json.type()) {
    case nlohmann::ordered_json::value_t::object: {
      py::dict dict;
      for (const auto& [key, value] : json.items()) dict[py::str(key)] = json_to_python(value);
      return dict;
    }
    case nlohmann::ordered_json::value_t::array: {
      py::list list;
      for (const auto& value : json) list.append(json_to_python(value));
      return list;
    }
    case nlohmann::ordered_json::value_t::string: return py::str(json.get_ref<const std::string&>());
    case nlohmann::ordered_json::value_t::boolean: return py::bool_(json.get<bool>());
    case nlohmann::ordered_json::value_t::number_integer: return py::int_(json.get<std::int64_t>());
    case nlohmann::ordered_json::value_t::number_unsigned: return py::int_(json.get<std::uint64_t>());
    case nlohmann::ordered_json::value_t::number_float: return py::float_(json.get<double>());
    case nlohmann::ordered_json::value_t::null:
    case nlohmann::ordered_json::value_t::binary:
    case nlohmann::ordered_json::value_t::discarded: break;
  }
  return py::none();
}

}  // namespace geodual::python
