// bad_setting(): the one error every settings group throws, naming the field.
#pragma once

#include <sstream>
#include <string>

#include "gpusolve/core/error.hpp"

namespace gpusolve::rbd::detail {

[[noreturn]] inline void bad_setting(const char* field, const std::string& why) {
  std::ostringstream os;
  os << "gpusolve: solver setting `" << field << "` " << why;
  throw InvalidArgumentError(os.str());
}

}  // namespace gpusolve::rbd::detail
