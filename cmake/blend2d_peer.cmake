# Blend2D as a peer in the benchmarks. It is not a Debian package: it joins the comparison only when
# -DVRASTER_BENCH_BLEND2D_ROOT names the install prefix of a build made outside this repository.
set(VRASTER_BENCH_BLEND2D_ROOT "" CACHE PATH "Install prefix of a Blend2D build to compare against (optional)")

# Links `target` with Blend2D and defines VRASTER_BENCH_WITH_BLEND2D=1 in it; true in `found` when that happened.
function(vraster_compare_with_blend2d target found)
  set(${found} FALSE PARENT_SCOPE)
  if(NOT VRASTER_BENCH_BLEND2D_ROOT)
    return()
  endif()
  find_package(blend2d CONFIG REQUIRED PATHS "${VRASTER_BENCH_BLEND2D_ROOT}" NO_DEFAULT_PATH)
  find_package(Threads REQUIRED)
  target_link_libraries(${target} PRIVATE blend2d::blend2d Threads::Threads ${CMAKE_DL_LIBS} rt)
  target_compile_definitions(${target} PRIVATE VRASTER_BENCH_WITH_BLEND2D=1)
  set(${found} TRUE PARENT_SCOPE)
endfunction()
