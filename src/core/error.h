// Error kinds that map to exit codes: bad input (2) versus internal failure (1).
#pragma once
#include <stdexcept>
#include <string>

namespace penumbra {

// A problem with what the user gave us. The message is one line and says where
// (file, JSON path or line) and what is wrong; the CLI exits with code 2.
class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace penumbra
