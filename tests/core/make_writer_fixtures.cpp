// SPDX-License-Identifier: BSD-3-Clause
// Writes the log fixtures of writer_fixtures.h (the loggers' own printf formats) into a tests/
// folder:
//   make_writer_fixtures TESTS_DIR
// writes TESTS_DIR/data/logs/NAME and a copy in TESTS_DIR/fuzz/corpus/TARGET/ for each fuzz
// target that takes it as a seed. tst_log_format regenerates the texts and compares them with the
// committed files.

#include <fstream>
#include <iostream>
#include <string>

#include "writer_fixtures.h"

namespace {

bool write(const std::string& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
  out.close();
  if (!out) {
    std::cerr << "make_writer_fixtures: cannot write " << path << "\n";
    return false;
  }
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: make_writer_fixtures TESTS_DIR\n";
    return 2;
  }
  const std::string tests = argv[1];
  for (const writer_fixtures::File& f : writer_fixtures::files()) {
    const std::string text = f.make();
    if (!write(tests + "/data/logs/" + f.name, text)) return 1;
    for (const std::string& target : f.corpora) {
      if (!write(tests + "/fuzz/corpus/" + target + "/" + f.name, text)) return 1;
    }
  }
  return 0;
}
