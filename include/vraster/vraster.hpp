// vraster: everything in one include.
#pragma once

#include "vraster/canvas.hpp"
#include "vraster/error.hpp"
#include "vraster/flatten.hpp"
#include "vraster/geometry.hpp"
#include "vraster/image.hpp"
#include "vraster/renderer.hpp"
#include "vraster/path.hpp"
#include "vraster/png.hpp"
#include "vraster/raster.hpp"
