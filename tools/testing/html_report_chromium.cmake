# ctest driver: hpsf diff --html makes a page that works in a real browser. Two small renders are compared; the
# page must reference nothing on the network, and headless Chromium must load it with no console output and no
# uncaught exception, draw every canvas (the page's script then sets data-ready="1" on <body>; an error handler
# installed before it records failures in data-errors), and take a non-trivial screenshot, kept in the build tree
# for a person to look at. Bad input (images of two sizes) must exit 3 and write no report.
# Inputs: HPSF, CHROMIUM (empty when CMake found none), OUT.
set(dir ${OUT}/html_report)
file(REMOVE_RECURSE ${dir})
file(MAKE_DIRECTORY ${dir})

function(run_hpsf)
  execute_process(COMMAND ${HPSF} ${ARGN} RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE err)
  set(code ${code} PARENT_SCOPE)
  set(out "${out}${err}" PARENT_SCOPE)
endfunction()

foreach(image a:1:64x64 b:2:64x64 small:1:32x32)
  string(REPLACE ":" ";" parts ${image})
  list(GET parts 0 name)
  list(GET parts 1 seed)
  list(GET parts 2 size)
  run_hpsf(render cornell --size ${size} --spp 4 --seed ${seed} -o ${dir}/${name}.exr)
  if(NOT code EQUAL 0)
    message(FATAL_ERROR "hpsf render ${name}: exit ${code}\n${out}")
  endif()
endforeach()

# Bad input: the check that refuses it runs after both images are read, and no report may be left behind.
run_hpsf(diff ${dir}/a.exr ${dir}/small.exr --html ${dir}/bad.html)
message("bad input: exit ${code}\n${out}")
if(NOT code EQUAL 3 OR NOT out MATCHES "small.exr is 32x32")
  message(FATAL_ERROR "hpsf diff of two sizes with --html: exit ${code}, expected 3 naming the file")
endif()
file(GLOB left ${dir}/bad.html ${dir}/.bad.html*)
if(left)
  message(FATAL_ERROR "bad input left ${left} behind")
endif()

set(page ${dir}/report.html)
run_hpsf(diff ${dir}/a.exr ${dir}/b.exr --html ${page})
message("hpsf diff --html: exit ${code}\n${out}")
if(NOT code EQUAL 2 OR NOT out MATCHES "wrote [^\n]*report.html")
  message(FATAL_ERROR "hpsf diff --html: exit ${code}, expected 2 (the seeds differ) and 'wrote ...report.html'")
endif()
run_hpsf(diff ${dir}/a.exr ${dir}/b.exr --html ${dir}/json.html --json)
if(NOT out MATCHES "\"outputs\": {[^}]*\"html\": \"[^\"]*json.html\"")
  message(FATAL_ERROR "hpsf diff --html --json: no outputs.html in\n${out}")
endif()

file(READ ${page} html)
foreach(reference "http://" "https://")
  string(FIND "${html}" "${reference}" at)
  if(NOT at EQUAL -1)
    message(FATAL_ERROR "${page} refers to ${reference} at byte ${at}: it must be self-contained")
  endif()
endforeach()

include(${CMAKE_CURRENT_LIST_DIR}/chromium_page.cmake)
chromium_check_page(${page} ${dir} 1400 1000 "data-ready=\"1\"" "data-canvases=\"4\"")
# A PNG of the window's size, and not an empty page: the dark page with a heading compresses to about 16 kB,
# the report with its images to about 150 kB (measured with Chromium 156).
file(READ ${screenshot} header LIMIT 24 HEX)
file(SIZE ${screenshot} bytes)
message("screenshot: ${screenshot}, ${bytes} bytes")
if(NOT header MATCHES "^89504e470d0a1a0a0000000d4948445200000578000003e8")
  message(FATAL_ERROR "${screenshot} is not a 1400x1000 PNG (header ${header})")
endif()
if(bytes LESS 60000)
  message(FATAL_ERROR "${screenshot} is ${bytes} bytes: the page shows next to nothing")
endif()
