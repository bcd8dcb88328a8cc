// Runs fn(i) for i in [0, n) on `threads` threads (the caller is one of
// them), handing out indices one at a time so uneven work balances. With
// threads <= 1 it is a plain loop. Worker threads persist between calls (one
// shared pool per process, grown on demand), so a call costs a wake-up, not a
// thread start. fn must be safe to call concurrently for different i; calls
// from several threads at once are serialised.
#pragma once

#include <cstddef>
#include <functional>

namespace surface_nbv {

void parallelForImpl(size_t n, int threads, const std::function<void(size_t)>& fn);

template <typename Fn>
void parallelFor(size_t n, int threads, Fn&& fn) {
  if (threads <= 1 || n < 2) {
    for (size_t i = 0; i < n; ++i) fn(i);
    return;
  }
  parallelForImpl(n, threads, std::function<void(size_t)>(std::forward<Fn>(fn)));
}

}  // namespace surface_nbv
