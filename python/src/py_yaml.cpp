// Python data -> YAML nodes for the strict readers of io/.
#include <fmt/format.h>

#include <cmath>

#include "io/format/input_error.hpp"
#include "python/src/bindings.hpp"

namespace pkmopt::python {
namespace {

// The text of a number that reads back to the same double ("0.1", "1e-05", "inf", "nan").
std::string float_text(double value) {
  if (std::isnan(value)) return ".nan";
  if (std::isinf(value)) return value > 0 ? ".inf" : "-.inf";
  return python_repr(py::float_(value));
}

YAML::Node to_node(py::handle value, const std::string& where, int depth) {
  if (depth > 64)
    throw InputError(fmt::format("{}: expected data nested at most 64 levels deep", where));
  if (value.is_none()) return YAML::Node(YAML::NodeType::Null);
  if (py::isinstance<py::bool_>(value)) return YAML::Node(value.cast<bool>() ? "true" : "false");
  if (py::isinstance<py::str>(value))
    return YAML::Node(text_from_python(value, where.empty() ? "value" : where));
  if (py::isinstance<py::int_>(value)) return YAML::Node(py::str(value).cast<std::string>());
  if (py::isinstance<py::float_>(value)) return YAML::Node(float_text(value.cast<double>()));
  // numpy scalars and arrays: their Python values (item / tolist).
  if (py::hasattr(value, "dtype") && py::hasattr(value, "tolist"))
    return to_node(value.attr("tolist")(), where, depth + 1);
  if (py::isinstance<py::dict>(value)) {
    YAML::Node map(YAML::NodeType::Map);
    for (const auto& [key, item] : value.cast<py::dict>()) {
      if (!py::isinstance<py::str>(key))
        throw InputError(
            fmt::format("{}: expected text keys, found the key {}", where, python_repr(key)));
      const std::string name = text_from_python(key, where.empty() ? "key" : where + " key");
      map[name] = to_node(item, where.empty() ? name : where + "." + name, depth + 1);
    }
    return map;
  }
  if (py::isinstance<py::list>(value) || py::isinstance<py::tuple>(value)) {
    YAML::Node sequence(YAML::NodeType::Sequence);
    std::size_t i = 0;
    for (const auto item : value) {
      sequence.push_back(to_node(item, fmt::format("{}[{}]", where, i), depth + 1));
      ++i;
    }
    return sequence;
  }
  throw InputError(fmt::format("{}: expected a dict, list, text, number, bool or None, found a {}",
                               where.empty() ? "the value" : where,
                               py::str(py::type::of(value).attr("__name__")).cast<std::string>()));
}

}  // namespace

YamlValue yaml_from_python(py::handle value, const std::string& name) {
  return YamlValue(to_node(value, "", 0), std::make_shared<const std::string>(name), "");
}

}  // namespace pkmopt::python
