// vraster_text: everything in one include.
#pragma once

#include "vraster_text/font.hpp"
#include "vraster_text/layout.hpp"
#include "vraster_text/render.hpp"
