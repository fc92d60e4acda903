#pragma once

#include <stdexcept>
#include <string>

namespace mpile {

/// A case file that cannot be run: the message names the file, the line, the key and what is wrong.
class CaseError : public std::runtime_error {
public:
  using std::runtime_error::runtime_error;
};

} // namespace mpile
