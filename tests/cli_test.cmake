# The vraster command-line tool: exit statuses, messages, "no output on failure", --bench output, demo.
# Run as: cmake -DVRASTER=<vraster binary> -DWORK=<scratch folder> -DSRC=<tests folder> -P cli_test.cmake
cmake_minimum_required(VERSION 3.25)

foreach(var VRASTER WORK SRC)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "cli_test.cmake: -D${var}=... is required")
  endif()
endforeach()

file(REMOVE_RECURSE "${WORK}")
file(MAKE_DIRECTORY "${WORK}")
set(DATA "${SRC}/data")
set(FAILURES "")

# Runs vraster with the given arguments in WORK; sets RC, OUT, ERR.
function(run_vraster)
  execute_process(COMMAND "${VRASTER}" ${ARGN}
                  WORKING_DIRECTORY "${WORK}"
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err
                  TIMEOUT 60)
  set(RC "${rc}" PARENT_SCOPE)
  set(OUT "${out}" PARENT_SCOPE)
  set(ERR "${err}" PARENT_SCOPE)
endfunction()

macro(fail what)
  list(APPEND FAILURES "${what}\n    exit status: ${RC}\n    stdout: ${OUT}\n    stderr: ${ERR}")
endmacro()

macro(expect_status case expected)
  if(NOT "${RC}" STREQUAL "${expected}")
    fail("${case}: exit status ${RC}, expected ${expected}")
  endif()
endmacro()

macro(expect_stderr case regex)
  if(NOT "${ERR}" MATCHES "${regex}")
    fail("${case}: stderr does not match '${regex}'")
  endif()
endmacro()

macro(expect_no_file case path)
  file(GLOB leftovers "${path}*")
  if(EXISTS "${path}" OR leftovers)
    fail("${case}: '${path}' (or a temporary next to it) exists after a failure: ${leftovers}")
  endif()
endmacro()

# Checks that `path` is a PNG of the given size, bit depth and colour type RGBA (6), reading its IHDR chunk.
macro(expect_png case path width height depth)
  if(NOT EXISTS "${path}")
    fail("${case}: '${path}' was not written")
  else()
    file(READ "${path}" header LIMIT 26 HEX)
    math(EXPR w_hex "${width}" OUTPUT_FORMAT HEXADECIMAL)
    math(EXPR h_hex "${height}" OUTPUT_FORMAT HEXADECIMAL)
    string(SUBSTRING "${header}" 0 16 signature)
    string(SUBSTRING "${header}" 24 8 chunk)
    string(SUBSTRING "${header}" 32 8 w_field)
    string(SUBSTRING "${header}" 40 8 h_field)
    string(SUBSTRING "${header}" 48 2 depth_field)
    string(SUBSTRING "${header}" 50 2 color_field)
    math(EXPR w_read "0x${w_field}")
    math(EXPR h_read "0x${h_field}")
    math(EXPR depth_read "0x${depth_field}")
    if(NOT signature STREQUAL "89504e470d0a1a0a" OR NOT chunk STREQUAL "49484452")
      fail("${case}: '${path}' is not a PNG (header ${header})")
    elseif(NOT w_read EQUAL ${width} OR NOT h_read EQUAL ${height} OR NOT depth_read EQUAL ${depth}
           OR NOT color_field STREQUAL "06")
      fail("${case}: '${path}' is ${w_read}x${h_read}, depth ${depth_read}, colour type ${color_field}; expected ${width}x${height}, depth ${depth}, type 06")
    endif()
  endif()
endmacro()

# --- malformed path data: SVG draws the path up to the error; a warning with FILE:LINE:COLUMN, status 0 ---
# tests/data/bad_path.svg line 3 is `  <path d="M1 1 L4 2 L5 x5 Z" fill="red"/>`: the 'x' is in column 25.
run_vraster(render "${DATA}/bad_path.svg" -o bad.png)
expect_status("malformed path data" 0)
expect_stderr("malformed path data" "bad_path\\.svg:3:25: ")
expect_stderr("malformed path data" "path data")
expect_stderr("malformed path data" "'x'")
expect_png("malformed path data" "${WORK}/bad.png" 8 6 8)
run_vraster(render "${DATA}/bad_path.svg" -o quiet.png --quiet)
expect_status("--quiet" 0)
if(NOT ERR STREQUAL "")
  fail("--quiet still printed warnings")
endif()

# The same error in a file written here: a multi-line d attribute, the error on its second line (line 4).
file(WRITE "${WORK}/multiline.svg"
  "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"10\" height=\"10\">\n"
  "<path fill=\"blue\"\n"
  "      d=\"M0 0 L10 0\n"
  "         L5 1..5 Z\"/>\n"
  "</svg>\n")
run_vraster(render multiline.svg -o multi.png)
expect_status("malformed multi-line path data" 0)
expect_stderr("malformed multi-line path data" "multiline\\.svg:4:[0-9]+: ")

# A document that cannot be used at all is still an error: no size.
file(WRITE "${WORK}/nosize.svg" "<svg xmlns=\"http://www.w3.org/2000/svg\">\n<path d=\"M0 0h1v1z\"/></svg>\n")
run_vraster(render nosize.svg -o nosize.png)
expect_status("no size" 2)
expect_stderr("no size" "nosize\\.svg:1:1: .*needs width and height")
expect_no_file("no size" "${WORK}/nosize.png")

# Malformed XML.
file(WRITE "${WORK}/broken.svg" "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"10\" height=\"10\">\n<path d=\"M0 0\"\n")
run_vraster(render broken.svg -o broken.png)
expect_status("malformed XML" 2)
expect_stderr("malformed XML" "broken\\.svg:[0-9]+:[0-9]+: ")
expect_no_file("malformed XML" "${WORK}/broken.png")

# --- missing input file ---
run_vraster(render "${WORK}/does-not-exist.svg" -o missing.png)
expect_status("missing input" 2)
expect_stderr("missing input" "does-not-exist\\.svg")
expect_stderr("missing input" "[Nn]o such file")
expect_no_file("missing input" "${WORK}/missing.png")

# --- usage errors ---
run_vraster(render "${DATA}/tiny.svg" -o usage.png --frobnicate)
expect_status("unknown option" 2)
expect_stderr("unknown option" "--frobnicate")
expect_no_file("unknown option" "${WORK}/usage.png")
foreach(args "render" "render;${DATA}/tiny.svg" "bogus-command" "render;${DATA}/tiny.svg;-o"
             "render;${DATA}/tiny.svg;-o;x.png;--depth;12" "render;${DATA}/tiny.svg;-o;x.png;--bench;0"
             "render;${DATA}/tiny.svg;-o;x.png;--bench;1.5" "render;${DATA}/tiny.svg;-o;x.png;--aa;fuzzy"
             "render;${DATA}/tiny.svg;-o;x.png;--rule;sometimes" "render;${DATA}/tiny.svg;-o;x.png;--tolerance;0"
             "demo;--nope")
  run_vraster(${args})
  expect_status("usage error '${args}'" 2)
  expect_stderr("usage error '${args}'" "vraster: ")
endforeach()
expect_no_file("usage errors" "${WORK}/x.png")
run_vraster()
expect_status("no command" 2)

# --- output that cannot be written ---
run_vraster(render "${DATA}/tiny.svg" -o "${WORK}/no/such/dir/out.png")
expect_status("unwritable output" 2)
expect_stderr("unwritable output" "no/such/dir/out\\.png")

# --- a valid tiny SVG ---
run_vraster(render "${DATA}/tiny.svg" -o tiny.png)
expect_status("valid SVG" 0)
expect_png("valid SVG" "${WORK}/tiny.png" 8 6 8)
run_vraster(render "${DATA}/tiny.svg" -o tiny16.png --depth 16 --aa none --rule evenodd --background white)
expect_status("valid SVG, 16 bits" 0)
expect_png("valid SVG, 16 bits" "${WORK}/tiny16.png" 8 6 16)
# Output sizes as rsvg-convert and resvg choose them: one side given keeps the aspect ratio (8x6 -> 300x225).
run_vraster(render "${DATA}/tiny.svg" -o wide.png -w 300)
expect_status("--width" 0)
expect_png("--width" "${WORK}/wide.png" 300 225 8)
run_vraster(render "${DATA}/tiny.svg" -o tall.png --height 7)
expect_status("--height" 0)
expect_png("--height" "${WORK}/tall.png" 10 7 8)
run_vraster(render "${DATA}/tiny.svg" -o both.png -w 5 -h 50)
expect_png("--width and --height" "${WORK}/both.png" 5 50 8)
run_vraster(render "${DATA}/tiny.svg" -o x.png -w 0)
expect_status("--width 0" 2)
run_vraster(render --help)
expect_status("render --help" 0)
if(NOT OUT MATCHES "--width")
  fail("render --help does not describe --width")
endif()
# compare: the conformance rule; an image against itself passes, against another size fails with status 1.
run_vraster(compare "${WORK}/wide.png" "${WORK}/wide.png")
expect_status("compare, same image" 0)
if(NOT OUT MATCHES "^pass pixels=67500 off=0 far_off=0")
  fail("compare, same image: unexpected figures")
endif()
run_vraster(compare "${WORK}/wide.png" "${WORK}/tiny.png" --diff "${WORK}/diff.png")
expect_status("compare, different sizes" 1)
expect_png("compare --diff" "${WORK}/diff.png" 300 225 8)
run_vraster(compare "${WORK}/wide.png" "${WORK}/missing.png")
expect_status("compare, missing file" 2)
file(GLOB partials "${WORK}/*.partial")
if(partials)
  list(APPEND FAILURES "temporary files left behind: ${partials}")
endif()

# --- --bench N: exactly one line on stdout ---
run_vraster(render "${DATA}/tiny.svg" --bench 3)
expect_status("--bench 3" 0)
if(NOT OUT MATCHES "^frames=3 ms_per_frame_median=[0-9.]+ ms_min=[0-9.]+\n$")
  fail("--bench 3: stdout is not exactly one line 'frames=3 ms_per_frame_median=... ms_min=...'")
endif()
run_vraster(render "${DATA}/tiny.svg" --bench 2 -o bench.png)
expect_status("--bench 2 with -o" 0)
if(NOT OUT MATCHES "^frames=2 ms_per_frame_median=[0-9.]+ ms_min=[0-9.]+\n$")
  fail("--bench 2 -o: stdout is not exactly one line")
endif()
expect_png("--bench 2 with -o" "${WORK}/bench.png" 8 6 8)

# --- demo ---
run_vraster(demo -o demo-out.png)
expect_status("demo" 0)
expect_png("demo" "${WORK}/demo-out.png" 640 400 8)

if(FAILURES)
  list(LENGTH FAILURES n)
  string(JOIN "\n  " text ${FAILURES})
  message(FATAL_ERROR "${n} CLI check(s) failed:\n  ${text}")
endif()
message(STATUS "all CLI checks passed")
