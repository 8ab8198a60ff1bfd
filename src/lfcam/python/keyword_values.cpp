// Python keyword arguments as lfcam's keyword values (cli/keyword_arguments.h): the one place
// the module turns Python objects into flag values, and refuses what no flag takes.
#include <fmt/format.h>
#include <pybind11/stl.h>

#include "lfcam/core/error.h"
#include "lfcam/python/bindings.h"

namespace lfcam::python {
namespace {

// A Python value as a keyword's value; anything else is a TypeError naming the keyword.
cli::KeywordValue KeywordValueOf(const std::string& name, const py::handle& value) {
  if (py::isinstance<py::bool_>(value)) return value.cast<bool>();
  if (py::isinstance<py::int_>(value)) {
    try {
      return value.cast<long long>();
    } catch (const py::cast_error&) {
      throw UsageError(
          fmt::format("{}: {} is out of range", name, py::str(value).cast<std::string>()));
    }
  }
  if (py::isinstance<py::float_>(value)) return value.cast<double>();
  if (py::isinstance<py::str>(value)) return value.cast<std::string>();
  if (py::hasattr(value, "__fspath__"))  // pathlib.Path: a file's name
    return py::str(value.attr("__fspath__")()).cast<std::string>();
  if (py::isinstance<py::sequence>(value) || py::hasattr(value, "__array__")) {
    std::vector<double> numbers;
    for (const py::handle item : py::iter(value)) {
      if (!py::isinstance<py::int_>(item) && !py::isinstance<py::float_>(item) &&
          !py::hasattr(item, "__float__"))
        throw py::type_error(fmt::format("{}: expected numbers, found {}", name,
                                         py::str(py::type::of(item)).cast<std::string>()));
      numbers.push_back(item.cast<double>());
      if (numbers.size() > 16) throw UsageError(fmt::format("{}: too many numbers", name));
    }
    return numbers;
  }
  throw py::type_error(fmt::format("{}: {} is not a value render takes", name,
                                   py::str(py::type::of(value)).cast<std::string>()));
}

}  // namespace

std::vector<cli::KeywordArgument> KeywordArguments(const py::kwargs& kwargs) {
  std::vector<cli::KeywordArgument> arguments;
  for (const auto& [key, value] : kwargs) {
    const std::string name = py::str(key).cast<std::string>();
    arguments.push_back({name, KeywordValueOf(name, value)});
  }
  return arguments;
}

}  // namespace lfcam::python
