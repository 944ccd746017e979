// hsr_identity: every render's line of hashes (identity.hpp), printed, for comparing
// targets (scripts/cross.sh) and for the suite's expected lines (tests/identity/check.cmake).
//   hsr_identity SCENES_DIR [--width W] [--random N] [--threads T] [--only SUBSTRING]
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

#include "identity/identity.hpp"

int main(int argc, char** argv) {
  if (argc < 2 || argc % 2 != 0) {
    std::fprintf(stderr, "usage: hsr_identity SCENES_DIR [--width W] [--random N] [--threads T] [--only SUBSTRING]\n");
    return 2;
  }
  hsr::identity::Options options;
  for (int i = 2; i + 1 < argc; i += 2) {
    if (!std::strcmp(argv[i], "--width")) options.width = std::atoi(argv[i + 1]);
    else if (!std::strcmp(argv[i], "--random")) options.randomScenes = std::atoi(argv[i + 1]);
    else if (!std::strcmp(argv[i], "--threads")) options.threads = std::atoi(argv[i + 1]);
    else if (!std::strcmp(argv[i], "--only")) options.only = argv[i + 1];
    else {
      std::fprintf(stderr, "hsr_identity: unknown option %s\n", argv[i]);
      return 2;
    }
  }
  hsr::identity::renderLines(argv[1], options, [](const std::string& line) { std::printf("%s\n", line.c_str()); });
  return 0;
}
