// shadowvol core: an option's value parsed by the names that to_string gives its enum.
//
// One loop and one message for every named enum (methods, generators, backends, ...):
// "unknown <what> '<name>': expected a, b or c", listing the values in the order given.
#pragma once

#include <initializer_list>
#include <string>
#include <string_view>

#include "core/expected.h"

namespace shadowvol {

// `to_string(E)` is found by argument-dependent lookup in E's namespace.
template <class E>
Expected<E> parse_name(std::string_view name, std::initializer_list<E> values,
                       std::string_view what) {
  std::string expected;
  std::size_t i = 0;
  for (E value : values) {
    if (name == to_string(value)) return value;
    expected += i == 0 ? "" : i + 1 == values.size() ? " or " : ", ";
    expected += to_string(value);
    ++i;
  }
  return make_error("unknown " + std::string(what) + " '" + std::string(name) +
                    "': expected " + expected);
}

}  // namespace shadowvol
