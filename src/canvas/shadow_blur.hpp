// A plain separable Gaussian blur of a float plane for canvas shadows (a stand-in until the shared blur lands).
#pragma once

#include <vector>

namespace vraster::canvas_detail {

/// How far (whole pixels) the blur of standard deviation `sigma` reaches: ceil(3 sigma), 0 for sigma <= 0.
int blur_reach(double sigma);

/// Blurs a width x height plane in place: the Gaussian sampled at whole-pixel offsets up to blur_reach(sigma),
/// normalised to sum 1, applied along rows then columns; outside the plane counts as 0. `scratch` is reused.
void gaussian_blur(std::vector<float>& plane, std::vector<float>& scratch, int width, int height, double sigma);

}  // namespace vraster::canvas_detail
