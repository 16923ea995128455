# Start-up: the dynamic loader's symbol walk (cmake/link_order.py says why).
# libanvil names the libraries deal.II pulls in, in the order of
# cmake/link_order.txt (most lookups answered first), so they enter the global
# scope in that order. Only libraries libdeal.ii loads anyway (its ldd): the
# set of loaded libraries, hence every symbol's definition, stays the same;
# a library missing here (another distribution) is left out.
option(ANVIL_LINK_ORDER "Order libanvil's DT_NEEDED by cmake/link_order.txt (faster start-up)" ON)

function(anvil_order_needed target)
  if(NOT ANVIL_LINK_ORDER OR NOT CMAKE_SYSTEM_NAME STREQUAL "Linux")
    return()
  endif()
  list(GET DEAL_II_LIBRARIES_RELEASE 0 _dealii)
  find_program(_ldd ldd)
  if(NOT _ldd OR NOT EXISTS "${_dealii}")
    return()
  endif()
  execute_process(COMMAND ${_ldd} ${_dealii} OUTPUT_VARIABLE _out RESULT_VARIABLE _status)
  if(NOT _status EQUAL 0)
    return()
  endif()
  file(STRINGS ${CMAKE_SOURCE_DIR}/cmake/link_order.txt _ranked REGEX "^[^#]")
  set(_paths "${_dealii}")
  foreach(_line ${_ranked})
    string(REGEX REPLACE "[ \t].*" "" _soname "${_line}")
    string(REGEX REPLACE "([.+])" "\\\\\\1" _pattern "${_soname}")
    if(_out MATCHES "[ \t]${_pattern} => ([^ \t\n]+)")
      list(APPEND _paths "${CMAKE_MATCH_1}")
    endif()
  endforeach()
  list(LENGTH _paths _n)
  message(STATUS "anvil: libanvil names ${_n} of deal.II's libraries in cmake/link_order.txt's order")
  # Link options come before the objects and every library on the link line,
  # so these lead the DT_NEEDED list; kept even if unused. Not in the link
  # interface: a program linking libanvil names libanvil first, and the BFS
  # reaches these right after that program's own few libraries.
  string(REPLACE ";" "," _list "${_paths}")
  target_link_options(${target} PRIVATE "LINKER:--push-state,--no-as-needed,${_list},--pop-state")
endfunction()
