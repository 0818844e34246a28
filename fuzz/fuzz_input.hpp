// SPDX-License-Identifier: MIT
#pragma once
// The readers take a path, so each fuzz input is written to a file first. A per-process file in
// /dev/shm (memory) keeps this cheap; the file is rewritten, never accumulated.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <string>
#include <unistd.h>

namespace rockjoint::fuzz
{
inline const std::string& input_path(const char* suffix)
{
  static const std::string path = "/dev/shm/rockjoint_fuzz_" + std::to_string(getpid()) + suffix;
  return path;
}

inline const std::string& write_input(const std::uint8_t* data, std::size_t size,
                                      const char* suffix)
{
  const std::string& path = input_path(suffix);
  std::FILE* f = std::fopen(path.c_str(), "wb");
  if (!f)
    __builtin_trap(); // the harness itself is broken: stop at once rather than fuzz nothing
  if (size && std::fwrite(data, 1, size, f) != size)
    __builtin_trap();
  std::fclose(f);
  return path;
}
} // namespace rockjoint::fuzz
