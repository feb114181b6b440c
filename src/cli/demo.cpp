// The embedded demo scene: fill rules, curves, arcs, transparency and fine detail in one picture.
#include "cli/cli.hpp"

namespace vraster::cli {

std::string_view demo_svg() {
  return R"SVG(<svg xmlns="http://www.w3.org/2000/svg" width="640" height="400" viewBox="0 0 640 400">
  <!-- backdrop -->
  <path d="M0 0H640V400H0Z" fill="#f4f1ea"/>
  <path d="M0 300C160 250 320 360 640 290V400H0Z" fill="#d9e4dd"/>
  <!-- the same pentagram under both fill rules -->
  <g transform="translate(20 20)">
    <path d="M80 0L127 145L4 55H156L33 145Z" fill="#c0392b" fill-rule="evenodd"/>
  </g>
  <g transform="translate(190 20)">
    <path d="M80 0L127 145L4 55H156L33 145Z" fill="#c0392b" fill-rule="nonzero"/>
  </g>
  <!-- curves and arcs -->
  <path d="M380 40c40-40 120-40 160 0s40 120 0 160-120 40-160 0-40-120 0-160z" fill="#2e86c1" fill-opacity="0.85"/>
  <path d="M420 80a40 40 0 1 0 80 0a40 40 0 1 0-80 0zM440 80a20 20 0 1 1 40 0a20 20 0 1 1-40 0z"
        fill="#f7dc6f" fill-rule="evenodd"/>
  <path d="M560 30q60 50 0 100t0 100" fill="none"/>
  <path d="M560 40l60 0l-30 52z" fill="#8e44ad" transform="rotate(15 590 60)"/>
  <!-- translucent overlaps -->
  <path d="M40 230a60 60 0 1 0 120 0a60 60 0 1 0-120 0z" fill="#e74c3c" fill-opacity="0.5"/>
  <path d="M100 230a60 60 0 1 0 120 0a60 60 0 1 0-120 0z" fill="#27ae60" fill-opacity="0.5"/>
  <path d="M70 280a60 60 0 1 0 120 0a60 60 0 1 0-120 0z" fill="#3498db" fill-opacity="0.5"/>
  <!-- a fan of thin slivers: antialiasing keeps their area -->
  <g transform="translate(420 330)">
    <path d="M0 0L180 -100L180 -98.6Z M0 0L180 -80L180 -79.3Z M0 0L180 -60L180 -59.65Z M0 0L180 -40L180 -39.8Z
             M0 0L180 -20L180 -19.9Z M0 0L180 0L180 0.05Z" fill="#1b2631"/>
  </g>
  <!-- strokes: joins, caps, dashes, and widths below a pixel that thin out instead of vanishing -->
  <path d="M370 250l30-30 30 30 30-30 30 30" fill="none" stroke="#c0392b" stroke-width="9" stroke-linejoin="round"
        stroke-linecap="round"/>
  <path d="M370 285l30-30 30 30 30-30 30 30" fill="none" stroke="#2c3e50" stroke-width="9" stroke-linejoin="miter"
        stroke-linecap="square"/>
  <path d="M540 140c40 30-40 60 0 90s-40 60 0 90" fill="none" stroke="#8e44ad" stroke-width="4"
        stroke-dasharray="12 6 2 6" stroke-linecap="round"/>
  <path d="M20 385H250M20 390H250M20 395H250" fill="none" stroke="#1b2631" stroke-width="0.3"/>
  <!-- concentric rings -->
  <path d="M300 300m-70 0a70 70 0 1 0 140 0a70 70 0 1 0-140 0zm10 0a60 60 0 1 1 120 0a60 60 0 1 1-120 0z
           m10 0a50 50 0 1 0 100 0a50 50 0 1 0-100 0zm10 0a40 40 0 1 1 80 0a40 40 0 1 1-80 0z
           m10 0a30 30 0 1 0 60 0a30 30 0 1 0-60 0zm10 0a20 20 0 1 1 40 0a20 20 0 1 1-40 0z" fill="#117a65"/>
</svg>
)SVG";
}

}  // namespace vraster::cli
