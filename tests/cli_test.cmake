# The vraster command-line tool: exit statuses, messages, "no output on failure", --bench output, demo.
# (What the written images hold is checked pixel by pixel in cli_pixels_test.cpp.)
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

# Every warning about something ignored names the element by FILE:LINE:COLUMN (one line each); --quiet
# silences them, in a batch too.
file(WRITE "${WORK}/ignored.svg"
  "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"10\" height=\"10\">\n"
  "  <blink/>\n"
  "  <rect width=\"5\" height=\"5\" fill=\"hsl(nope)\" opacity=\"0.1mm\"/>\n"
  "  <rect width=\"abc\" height=\"5\" filter=\"url(#f)\"/>\n"
  "  <polygon points=\"0 0 5 5 9\" stroke-linecap=\"miter\"/>\n"
  "  <path d=\"M0 0 L5 5 Q\" fill=\"url(#missing)\"/>\n"
  "  <rect width=\"5\" height=\"5\" mask=\"url(#no-mask)\" clip-path=\"url(#no-clip)\"/>\n"
  "</svg>\n")
run_vraster(render ignored.svg -o ignored.png --no-system-fonts)
expect_status("ignored values" 0)
string(REGEX MATCHALL "[^\n]+" warning_lines "${ERR}")
list(LENGTH warning_lines warning_count)
if(warning_count LESS 7)
  fail("ignored values: expected a warning for each of the 7 lines with ignored things, got ${warning_count}")
endif()
foreach(line IN LISTS warning_lines)
  if(NOT line MATCHES "^ignored\\.svg:[2-7]:[0-9]+: ")
    fail("ignored values: a warning without ignored.svg:LINE:COLUMN: '${line}'")
  endif()
endforeach()
foreach(line_number 2 3 4 5 6 7)
  if(NOT ERR MATCHES "ignored\\.svg:${line_number}:")
    fail("ignored values: nothing reported on line ${line_number}")
  endif()
endforeach()
file(MAKE_DIRECTORY "${WORK}/quiet_batch")
run_vraster(render ignored.svg "${DATA}/bad_path.svg" -o quiet_batch/ -j 2 --quiet)
expect_status("--quiet batch" 0)
if(NOT ERR STREQUAL "")
  fail("--quiet batch still printed: ${ERR}")
endif()
expect_png("--quiet batch" "${WORK}/quiet_batch/bad_path.png" 8 6 8)

# -o - (standard output): a failure writes nothing there.
run_vraster(render broken.svg -o -)
expect_status("-o -, malformed XML" 2)
if(NOT OUT STREQUAL "")
  fail("-o -, malformed XML: something was written on standard output")
endif()

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
             "render;${DATA}/tiny.svg;-o;x.png;--threads;0" "render;${DATA}/tiny.svg;-o;x.png;--threads;65"
             "render;${DATA}/tiny.svg;-o;x.png;--threads;1.5"
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
# --help and -? on every subcommand: its own usage on stdout, status 0 (-h stays render's --height, as in
# rsvg-convert: see "--height" above).
foreach(command render explain fill-rules text accuracy compare mesh shading depth demo)
  foreach(flag --help -?)
    run_vraster(${command} ${flag})
    expect_status("${command} ${flag}" 0)
    if(NOT OUT MATCHES "^usage: vraster ${command} ")
      fail("${command} ${flag}: stdout does not start with 'usage: vraster ${command} '")
    endif()
  endforeach()
endforeach()
run_vraster(render "${DATA}/tiny.svg" -o help_not_written.png --help)
expect_status("render IN -o OUT --help" 0)
expect_no_file("render IN -o OUT --help" "${WORK}/help_not_written.png")
run_vraster(--help)
expect_status("vraster --help" 0)
foreach(command render explain fill-rules text accuracy compare mesh shading depth demo)
  if(NOT OUT MATCHES "\n  vraster ${command} ")
    fail("vraster --help does not list '${command}'")
  endif()
endforeach()
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
# Frames after the first redraw only the tiles the plan touches (draw_frame): the image is the one-frame render.
run_vraster(render "${DATA}/corner.svg" -o corner_once.png --background "#eeeedd")
expect_status("corner once" 0)
run_vraster(render "${DATA}/corner.svg" --bench 3 -o corner_frames.png --background "#eeeedd")
expect_status("corner --bench 3" 0)
file(SHA256 "${WORK}/corner_once.png" once_hash)
file(SHA256 "${WORK}/corner_frames.png" frames_hash)
if(NOT once_hash STREQUAL frames_hash)
  fail("--bench 3: the last of three frames differs from a single render")
endif()

# --- mesh, shading, depth ---
run_vraster(mesh "${SRC}/../samples/colour_wheel.vmesh" -o wheel.png --aa)
expect_status("mesh .vmesh sample" 0)
expect_png("mesh .vmesh sample" "${WORK}/wheel.png" 320 240 8)
run_vraster(mesh "${SRC}/../samples/pyramid.obj" -o pyramid.png --camera perspective --width 96 --height 64
            --shading phong --bits 16 --depth painter)
expect_status("mesh OBJ sample" 0)
expect_png("mesh OBJ sample" "${WORK}/pyramid.png" 96 64 16)
run_vraster(shading -o shading.png --panel 40)
expect_status("shading sheet" 0)
expect_png("shading sheet" "${WORK}/shading.png" 168 138 8)
run_vraster(depth -o depth.png --panel 40)
expect_status("depth sheet" 0)
expect_png("depth sheet" "${WORK}/depth.png" 116 138 8)
# Bad mesh files: FILE:LINE:COLUMN, exit status 2, no output file.
file(WRITE "${WORK}/bad_number.vmesh" "vmesh 1\nv 1 2 0 #ff0000\nv 3 x4 0 #00ff00\n")
file(WRITE "${WORK}/bad_index.vmesh" "vmesh 1\nv 1 2 0 #ff0000\nv 3 4 0 #00ff00\nv 5 1 0 #0000ff\nt 0 1 3\n")
file(WRITE "${WORK}/bad_colour.vmesh" "vmesh 1\n  v 1 2 0 red\n")
file(WRITE "${WORK}/no_header.vmesh" "v 1 2 0 #ff0000\n")
file(WRITE "${WORK}/infinite.vmesh" "vmesh 1\nv 1 inf 0 #ff0000\n")
file(WRITE "${WORK}/huge.vmesh" "vmesh 1\nsize 100000 10\n")
file(WRITE "${WORK}/bad_face.obj" "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n")
file(WRITE "${WORK}/zero_index.obj" "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 0 3\n")
file(WRITE "${WORK}/no_faces.obj" "v 0 0 0\n")
foreach(case "bad_number.vmesh;:3:5: " "bad_index.vmesh;:5:7: .*vertex 3" "bad_colour.vmesh;:2:11: .*colour"
             "no_header.vmesh;:1:1: .*vmesh 1" "infinite.vmesh;:2:5: .*not finite" "huge.vmesh;:2:6: .*width"
             "bad_face.obj;:4:7: .*out of range" "zero_index.obj;:4:5: " "no_faces.obj;no faces")
  list(GET case 0 file)
  list(GET case 1 regex)
  run_vraster(mesh ${file} -o mesh_out.png)
  expect_status("mesh ${file}" 2)
  expect_stderr("mesh ${file}" "${regex}")
  expect_no_file("mesh ${file}" "${WORK}/mesh_out.png")
endforeach()
run_vraster(mesh "${SRC}/../samples/pyramid.obj" -o mesh_out.png --shading glossy)
expect_status("mesh unknown shading" 2)
expect_no_file("mesh unknown shading" "${WORK}/mesh_out.png")

# --- demo ---
run_vraster(demo -o demo-out.png)
expect_status("demo" 0)
expect_png("demo" "${WORK}/demo-out.png" 640 620 8)

# --- hostile input (issue 12): uncaught exceptions, output files, input size caps ---
execute_process(COMMAND ${CMAKE_COMMAND} -E env VRASTER_BENCH_SCENES=/nonexistent "${VRASTER}" accuracy -o acc_missing
                WORKING_DIRECTORY "${WORK}" RESULT_VARIABLE RC OUTPUT_VARIABLE OUT ERROR_VARIABLE ERR TIMEOUT 60)
expect_status("VRASTER_BENCH_SCENES=/nonexistent vraster accuracy -o D" 2)
expect_stderr("VRASTER_BENCH_SCENES=/nonexistent vraster accuracy -o D" "VRASTER_BENCH_SCENES='/nonexistent' is not a directory")
expect_no_file("VRASTER_BENCH_SCENES=/nonexistent vraster accuracy -o D" "${WORK}/acc_missing/accuracy.png")

# accuracy from a deleted working directory: std::filesystem threw and the program aborted.
execute_process(COMMAND sh -c "mkdir -p '${WORK}/gone' && cd '${WORK}/gone' && rmdir '${WORK}/gone' && exec \"$0\" accuracy -o D"
                        "${VRASTER}"
                RESULT_VARIABLE RC OUTPUT_VARIABLE OUT ERROR_VARIABLE ERR TIMEOUT 120)
expect_status("accuracy from a deleted working directory" 2)
expect_stderr("accuracy from a deleted working directory" "^vraster: accuracy: cannot create directory 'D'")

# accuracy -o D: both files or neither (here accuracy.md cannot be written: it is a directory).
file(MAKE_DIRECTORY "${WORK}/acc_half/accuracy.md")
run_vraster(accuracy "${DATA}/tiny.svg" -o acc_half --frames 1)
expect_status("accuracy -o D when a later file fails" 2)
expect_no_file("accuracy -o D when a later file fails" "${WORK}/acc_half/accuracy.png")

# A symlink at the old fixed temporary name must not be followed; an existing .partial file is not taken over.
file(WRITE "${WORK}/victim" "")
file(CREATE_LINK "${WORK}/victim" "${WORK}/linked.png.partial" SYMBOLIC)
run_vraster(render "${DATA}/tiny.svg" -o linked.png)
expect_status("symlink out.png.partial -> victim" 0)
file(SIZE "${WORK}/victim" victim_size)
if(NOT victim_size EQUAL 0 OR NOT IS_SYMLINK "${WORK}/linked.png.partial")
  fail("symlink out.png.partial -> victim: the victim was written (${victim_size} bytes) or the link replaced")
endif()
expect_png("symlink out.png.partial -> victim" "${WORK}/linked.png" 8 6 8)
file(WRITE "${WORK}/taken.png.partial" "keep me")
run_vraster(render "${DATA}/tiny.svg" -o taken.png)
file(READ "${WORK}/taken.png.partial" kept)
if(NOT kept STREQUAL "keep me")
  fail("existing a.png.partial: it was taken over")
endif()
file(GLOB leftovers "${WORK}/*.partial")
list(REMOVE_ITEM leftovers "${WORK}/taken.png.partial" "${WORK}/linked.png.partial")
if(leftovers)
  fail("temporary files left behind: ${leftovers}")
endif()

# -o /dev/full: written through (an error: no space), never replaced by a regular file.
if(EXISTS /dev/full)
  run_vraster(render "${DATA}/tiny.svg" -o /dev/full)
  expect_status("-o /dev/full" 2)
  expect_stderr("-o /dev/full" "cannot write '/dev/full': No space left on device")
  execute_process(COMMAND stat -c %F /dev/full OUTPUT_VARIABLE kind OUTPUT_STRIP_TRAILING_WHITESPACE)
  if(NOT kind STREQUAL "character special file")
    fail("-o /dev/full: /dev/full is now a ${kind}")
  endif()
endif()

# A read-only target keeps its mode (it used to become 0644).
file(WRITE "${WORK}/readonly.png" "old")
file(CHMOD "${WORK}/readonly.png" PERMISSIONS OWNER_READ GROUP_READ WORLD_READ)
run_vraster(render "${DATA}/tiny.svg" -o readonly.png)
expect_status("read-only target" 0)
execute_process(COMMAND stat -c %a "${WORK}/readonly.png" OUTPUT_VARIABLE mode OUTPUT_STRIP_TRAILING_WHITESPACE)
if(NOT mode STREQUAL "444")
  fail("read-only target: mode ${mode} after writing, expected 444")
endif()
expect_png("read-only target" "${WORK}/readonly.png" 8 6 8)

# Inputs without an end: the size caps stop them.
run_vraster(render /dev/zero -o zero.png)
expect_status("vraster render /dev/zero" 2)
expect_stderr("vraster render /dev/zero" "larger than the limit of 64 MiB")
expect_no_file("vraster render /dev/zero" "${WORK}/zero.png")

if(FAILURES)
  list(LENGTH FAILURES n)
  string(JOIN "\n  " text ${FAILURES})
  message(FATAL_ERROR "${n} CLI check(s) failed:\n  ${text}")
endif()
message(STATUS "all CLI checks passed")
