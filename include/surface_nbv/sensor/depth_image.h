// A depth image: row-major float z in metres, NaN where there is no return.
#pragma once

#include <cmath>
#include <limits>
#include <vector>

namespace surface_nbv {

struct DepthImage {
  int width = 0;
  int height = 0;
  std::vector<float> data;

  void resize(int w, int h) {
    width = w;
    height = h;
    data.assign(static_cast<size_t>(w) * h, std::numeric_limits<float>::quiet_NaN());
  }
  float at(int row, int col) const { return data[static_cast<size_t>(row) * width + col]; }
  float& at(int row, int col) { return data[static_cast<size_t>(row) * width + col]; }
  size_t validCount() const {
    size_t n = 0;
    for (float z : data) n += std::isfinite(z) ? 1 : 0;
    return n;
  }
};

}  // namespace surface_nbv
