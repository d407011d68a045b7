// The main of each numbered example program: runs the example(s) linked into it and writes the pictures into the
// folder given as the first argument (default: the current folder). The shared data is found as `tessera gallery`
// finds it without --data (locate_shared_data).
#include <cstdio>
#include <exception>

#include "gallery.hpp"

int main(int argc, char** argv) {
  try {
    const size_t n = tessera::examples::run_examples(argc > 1 ? argv[1] : ".").pictures;
    std::printf("%zu picture(s) written\n", n);
    return n > 0 ? 0 : 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "example: error: %s\n", e.what());
    return 1;
  }
}
