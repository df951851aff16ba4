# What the HTML pages' browser tests share: load a page in headless Chromium and require that it logs nothing to
# the console, throws nothing, records no error in <body data-errors> and sets the <body> attributes its script sets
# when done; then take a screenshot of the window's size, kept beside it for a person to look at.
# chromium_check_page(PAGE DIR WIDTH HEIGHT ATTRIBUTE...) requires each ATTRIBUTE (name="value") on <body>, and
# sets `dom` and `screenshot` in the caller.
# Inputs: CHROMIUM (empty when CMake found none).
function(chromium_check_page page dir width height)
  if(NOT CHROMIUM)
    message(FATAL_ERROR
            "no Chromium (chromium, chromium-browser or google-chrome); scripts/install-deps.sh installs it")
  endif()
  # Chromium as root needs --no-sandbox; a profile of its own so that parallel tests do not share one.
  set(chromium ${CHROMIUM} --headless=new --no-sandbox --disable-gpu --no-first-run --disable-extensions
    --user-data-dir=${dir}/profile --virtual-time-budget=10000)
  execute_process(COMMAND ${chromium} --enable-logging=stderr --v=0 --dump-dom file://${page}
    RESULT_VARIABLE code OUTPUT_VARIABLE dom ERROR_VARIABLE log TIMEOUT 120)
  file(WRITE ${dir}/dom.html "${dom}")
  file(WRITE ${dir}/chromium.log "${log}")
  if(NOT code EQUAL 0)
    message(FATAL_ERROR "chromium --dump-dom: exit ${code}\n${log}")
  endif()
  string(REGEX MATCH "<body[^>]*>" body "${dom}")
  message("the page's body after its script ran: ${body}")
  # The page logs nothing when it works: any console line from it is a failure, as is any uncaught exception.
  get_filename_component(name ${page} NAME)
  string(REPLACE "." "\\." name "${name}")
  string(REGEX MATCHALL "[^\n]*(CONSOLE[^\n]*${name}|Uncaught)[^\n]*" console "${log}")
  if(console)
    string(REPLACE ";" "\n" console "${console}")
    message(FATAL_ERROR "the page wrote to the console or threw:\n${console}")
  endif()
  if(body MATCHES "data-errors=\"([^\"]*)\"")
    message(FATAL_ERROR "the page recorded errors: ${CMAKE_MATCH_1}")
  endif()
  foreach(attribute IN LISTS ARGN)
    string(FIND "${body}" " ${attribute}" at)
    if(at EQUAL -1)
      message(FATAL_ERROR "the page's script did not finish: no ${attribute} on ${body}")
    endif()
  endforeach()

  get_filename_component(stem ${page} NAME_WE)
  set(shot ${dir}/${stem}.png)
  execute_process(COMMAND ${chromium} --hide-scrollbars --window-size=${width},${height} --screenshot=${shot}
                          file://${page}
    RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE log TIMEOUT 120)
  if(NOT code EQUAL 0 OR NOT EXISTS ${shot})
    message(FATAL_ERROR "chromium --screenshot: exit ${code}, no ${shot}\n${log}")
  endif()
  set(dom "${dom}" PARENT_SCOPE)
  set(screenshot ${shot} PARENT_SCOPE)
endfunction()
