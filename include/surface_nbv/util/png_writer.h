// Minimal PNG encoder (8-bit grey or RGB, zlib-deflated) so tools can write
// pictures people can open without pulling in an imaging library.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "surface_nbv/util/status.h"

namespace surface_nbv {

// `pixels` is row-major, `channels` (1 = grey, 3 = RGB) bytes a pixel.
Status writePng(const std::string& path, int width, int height, int channels, const std::vector<uint8_t>& pixels);

// Maps depth in [lo, hi] to a perceptual colour ramp (near = yellow, far =
// purple); non-finite depth is black. Returns RGB bytes, row-major.
std::vector<uint8_t> colorizeDepth(const std::vector<float>& depth, float lo, float hi);

}  // namespace surface_nbv
