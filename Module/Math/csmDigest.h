// SPDX-License-Identifier: BSD-3-Clause
// A digest of bytes: whether data seen before (a mesh's cells, its triangles) is the same now,
// without keeping a copy of it. Pure C++, no VTK, no GL.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>

namespace csm
{

/// Folds `bytes` bytes at `data` (with their count) into `digest`: 64 bits mixed a word at a time
/// (FNV-1a's prime, with a shift), so that equal bytes give equal digests and different ones
/// differ but with a chance of about 2^-64.
inline void digestBytes(const void* data, std::size_t bytes, std::uint64_t& digest)
{
  const unsigned char* p = static_cast<const unsigned char*>(data);
  digest = (digest ^ bytes) * 0x9e3779b97f4a7c15ull;
  std::size_t i = 0;
  for (; i + 8 <= bytes; i += 8)
  {
    std::uint64_t word;
    std::memcpy(&word, p + i, 8);
    digest = (digest ^ word) * 0x100000001b3ull;
    digest ^= digest >> 29;
  }
  for (; i < bytes; ++i)
  {
    digest = (digest ^ p[i]) * 0x100000001b3ull;
  }
}

} // namespace csm
