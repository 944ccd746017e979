// Two kinds of failure, two mechanisms (after pbrt):
//  - InputError: the user's input is wrong. The message is one line saying what,
//    where (file, line, key) and what was expected; the CLI prints it and exits 2.
//  - HSR_CHECK: a programmer's invariant. Failing it is a bug in hsr, never in the input.
#pragma once

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
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

// The whole of a user's input file (`what`: "scene", "OBJ"), or InputError. Only a
// regular file is opened: a device or a pipe (/dev/zero, /dev/stdin) would be read forever.
inline std::string readInputFile(const std::filesystem::path& file, const std::string& what) {
  std::error_code error;
  if (!std::filesystem::is_regular_file(file, error))
    throw InputError(file.string() + ": cannot open the " + what + " file (missing, or not a regular file)");
  std::ifstream in(file, std::ios::binary);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (!in.is_open() || in.bad()) throw InputError(file.string() + ": cannot read the " + what + " file");
  return text;
}

}  // namespace hsr

#define HSR_CHECK(condition) \
  ((condition) ? (void)0 : ::hsr::checkFailed(#condition, __FILE__, __LINE__))
