// Two kinds of failure, two mechanisms (see ../shared/STYLE.md, after pbrt):
//  - InputError: the user's input is wrong. The message is one line saying what,
//    where (file, line, key) and what was expected; the CLI prints it and exits 2.
//  - HSR_CHECK: a programmer's invariant. Failing it is a bug in hsr, never in the input.
#pragma once

#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <string>

namespace hsr {

class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

[[noreturn]] inline void checkFailed(const char* condition, const char* file, int line) {
  std::fprintf(stderr, "hsr: internal error: %s:%d: check failed: %s\n", file, line, condition);
  std::abort();
}

}  // namespace hsr

#define HSR_CHECK(condition) \
  ((condition) ? (void)0 : ::hsr::checkFailed(#condition, __FILE__, __LINE__))
