// Where a command's text report goes: standard output, or a file written atomically (--out).
#pragma once

#include <iostream>
#include <string>

#include "base/atomic_file.hpp"

namespace skyspec::cli {

inline void print_or_write(const std::string& text, const std::string& out_path) {
  if (out_path.empty())
    std::cout << text;
  else
    write_file_atomically(out_path, text);
}

}  // namespace skyspec::cli
