#pragma once
// The message of the spread::Error a call throws ("" when it throws none): the tests of refusals compare it.
#include <string>

#include "libspread/core/error.hpp"

namespace spread::testing {

template <typename F>
std::string error_of(F f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

}  // namespace spread::testing
