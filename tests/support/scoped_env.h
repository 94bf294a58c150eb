// An environment variable set for the commands a test runs (system() and fork pass
// it on), put back as it was when the test's scope ends.
#pragma once
#include <cstdlib>
#include <optional>
#include <string>

namespace penumbra::testing {

class ScopedEnv {
 public:
  ScopedEnv(const char* name, const std::string& value) : name_(name) {
    if (const char* old = std::getenv(name)) old_ = old;
    ::setenv(name, value.c_str(), 1);
  }
  ~ScopedEnv() {
    if (old_) ::setenv(name_, old_->c_str(), 1);
    else ::unsetenv(name_);
  }

 private:
  const char* name_;
  std::optional<std::string> old_;
};

}  // namespace penumbra::testing
