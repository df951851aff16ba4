# ctest driver: the page hpsf sweep writes (OUT/sweep.html) works in a real browser. A small sweep of two filter
# widths and one and two frames; the page names no address but uPlot's licence banner (it loads nothing), lists every configuration, and
# headless Chromium loads it with no console output and no uncaught exception and draws its four charts (the page's
# script sets data-ready="1" and data-charts="4" on <body>, an error handler records failures in data-errors); a
# screenshot is kept in the build tree for a person to look at.
# Inputs: HPSF, CHROMIUM (empty when CMake found none), OUT.
set(dir ${OUT}/sweep_html)
file(REMOVE_RECURSE ${dir})
file(MAKE_DIRECTORY ${dir})
# The grid goes in quoted: as a list argument it would split at its semicolons.
execute_process(COMMAND ${HPSF} sweep cornell --grid "spp=1,4; frames=1,2; filter-width=2,4; method=pt,hpsf,radius"
                        --size 24x24 --seeds 2 --reference-spp 32 --cache ${dir}/cache --out ${dir}/sweep
                RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT code EQUAL 0)
  message(FATAL_ERROR "hpsf sweep: exit ${code}\n${out}${err}")
endif()
set(page ${dir}/sweep/sweep.html)
file(READ ${page} html)
string(REGEX MATCHALL "https?://[^\"' )]*" addresses "${html}")
list(REMOVE_DUPLICATES addresses)
if(NOT addresses STREQUAL "https://github.com/leeoniya/uPlot")
  message(FATAL_ERROR "${page} names addresses other than uPlot's banner: ${addresses}")
endif()
string(REGEX MATCHALL "<tr><td>method=" rows "${html}")
list(LENGTH rows rows)
if(NOT rows EQUAL 20)  # pt at 2 spp and 2 frame counts, hpsf and radius at those x 2 widths
  message(FATAL_ERROR "the page's table has ${rows} configurations, not 20")
endif()

include(${CMAKE_CURRENT_LIST_DIR}/chromium_page.cmake)
chromium_check_page(${page} ${dir} 1400 1300 "data-ready=\"1\"" "data-charts=\"4\"")
# uPlot draws each chart on a canvas.
string(REGEX MATCHALL "<canvas" canvases "${dom}")
list(LENGTH canvases canvases)
if(NOT canvases EQUAL 4)
  message(FATAL_ERROR "the page has ${canvases} canvases, not 4")
endif()
file(SIZE ${screenshot} bytes)
message("screenshot: ${screenshot}, ${bytes} bytes")
# The page with its charts compresses to about 150 kB; a page without them to about 60 kB (Chromium 156).
if(bytes LESS 90000)
  message(FATAL_ERROR "${screenshot} is ${bytes} bytes: the charts are missing")
endif()
