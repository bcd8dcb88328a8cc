// parallelFor over runs of `chunk` consecutive indices: fn(i) for i in
// [0, n) with each thread taking `chunk` indices at a time, so that threads
// write to distant parts of per-index output arrays (no false sharing) and
// cheap items pay one hand-out each per chunk. Same contract as parallelFor.
#pragma once

#include <algorithm>
#include <cstddef>

#include "surface_nbv/util/parallel_for.h"

namespace surface_nbv {

template <typename Fn>
void parallelForChunked(size_t n, int threads, size_t chunk, Fn&& fn) {
  chunk = std::max<size_t>(chunk, 1);
  parallelFor((n + chunk - 1) / chunk, threads, [&](size_t c) {
    const size_t end = std::min(n, (c + 1) * chunk);
    for (size_t i = c * chunk; i < end; ++i) fn(i);
  });
}

}  // namespace surface_nbv
